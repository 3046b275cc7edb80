#!/usr/bin/env python3
"""indep_claims.py RUN_DIR INDEP - every row of claims.json against a value derived outside
the program, and its verdict against the one that value gives under the claim's tolerance,
written here from the paper's printed digits (one unit in the last printed digit unless the
row says otherwise). Sources, per row, beside it:
  - closed forms worked by hand (eq. 11-12 after u = cos x, coef(n), the zone end of f2, the
    zeros of eq. 14, the albedo closed forms),
  - least squares written here (the fits of k_Q(n) and coef(n)),
  - brute force in tests/indep.c (a grid + golden-section search over both zones of every n,
    from tests/lobe_formulas.h, the formulas written a second time).
Prints one line per failed row and exits 1 when any row fails."""
import json
import math
import subprocess
import sys
from fractions import Fraction

run, indep = sys.argv[1], sys.argv[2]


def no_const(x):
    raise ValueError("non-finite number in JSON: " + x)


claims = json.load(open(run + "/claims.json"), parse_constant=no_const)
energy = json.load(open(run + "/energy.json"), parse_constant=no_const)
rows = {r["id"]: r for r in claims["claims"]}
failures = []
checked = set()


def fail(rid, msg):
    failures.append("%s: %s" % (rid, msg))


def row(rid):
    checked.add(rid)
    if rid not in rows:
        fail(rid, "row missing from claims.json")
        return None
    return rows[rid]


def verdict(ok):
    return "reproduced" if ok else "not reproduced"


def number_row(rid, value, claimed, tol, rel=1e-9, absolute=None, within=None, worded=False):
    """A row whose measured value is `value` (derived here): measured within rel (or absolute)
    of it, claimed as printed, verdict = |value - claimed| <= tol (or within(value))."""
    r = row(rid)
    if r is None:
        return
    m = r["measured"]
    lim = absolute if absolute is not None else rel * abs(value)
    if m is None or abs(m - value) > lim:
        fail(rid, "measured %r, derived here %r (tolerance %g)" % (m, value, lim))
    if claimed is not None and (r["claimed"] is None or abs(r["claimed"] - claimed) > 1e-12 * max(1, abs(claimed))):
        fail(rid, "claimed %r, the paper prints %r" % (r["claimed"], claimed))
    # the tolerance the row prints (what a reader checks the verdict against) is the one used here
    t = r["tolerance"]
    if within is None and t.startswith("+-"):
        word = t[2:].split()[0]
        printed = float(word[:-1]) / 100 if word.endswith("%") else float(word)
        if abs(printed - tol) > 1e-9 * tol:
            fail(rid, "prints the tolerance %r, one unit in the claim's last printed digit is %g" % (t, tol))
    elif within is None and not worded:
        fail(rid, "tolerance %r is not of the form +-X" % t)
    ok = within(value) if within else abs(value - claimed) <= tol * (1 + 1e-12)
    if r["verdict"] != verdict(ok):
        fail(rid, "verdict %r, expected %r (derived %r against %r +- %g)" % (r["verdict"], verdict(ok), value,
                                                                         claimed, tol))


def relation_row(rid, ok, why):
    r = row(rid)
    if r is not None and r["verdict"] != verdict(ok):
        fail(rid, "verdict %r, expected %r: %s" % (r["verdict"], verdict(ok), why))


# ---- paper 1, eq. 11-12: with u = cos x and h = 1 - c_e, c_e = exp(-0.511/n), the inner
# integrals are closed forms (worked by hand; test_reproduce.c states them), the outer one
# over n in [16, 256] is Simpson's rule with 4000 panels (error below 1e-10).
def inner(n, term):
    h = -math.expm1(-0.511 / n)
    return [-math.expm1(-0.511 * (n + 2) / n) / (n + 2),          # int u^(n+1) du
            n * n * (h ** 3 / 3 - h ** 4 / 4),                     # xi^2: n^2 (u-1)^2 u
            2 * n * -(h * h / 2 - h ** 3 / 3),                     # xi: 2n (u-1) u
            h - h * h / 2][term]                                   # 1: u


def simpson(f, lo, hi, panels=4000):
    step = (hi - lo) / panels
    s = f(lo) + f(hi) + sum((4 if i % 2 else 2) * f(lo + i * step) for i in range(1, panels))
    return s * step / 3


eq = [simpson(lambda n, t=t: inner(n, t), 16, 256) for t in range(4)]
number_row("P1-eq11-lhs", eq[0], 1.098, 0.001)
number_row("P1-eq12-a", eq[1], 0.12026, 1e-5)
number_row("P1-eq12-b", eq[2], -0.71068, 1e-5)
number_row("P1-eq12-c", eq[3], 1.40119, 1e-5)
# xi: the smaller root of eq[1] xi^2 + eq[2] xi + eq[3] - eq[0] = 0.
a, b, c = eq[1], eq[2], eq[3] - eq[0]
xi = (-b - math.sqrt(b * b - 4 * a * c)) / (2 * a)
number_row("P1-xi", xi, 0.463, 0.001)
# 29/64 is the nearest 64th of 0.463 only if it is within 1/128 of it (it is 0.009875 away).
number_row("P1-xi64", 29 / 64, 0.463, 1 / 128, rel=0, worded=True)
# eq. 14: the paper's zero acos((29n - 64)/(29n)) at n = 16 against F_VOL's own zero, where
# 0.463 n (c - 1) + 1 = 0: acos(1 - 1/(0.463 n)); an identity, so +-1e-9 rad.
eq14_claimed = math.acos((29 * 16 - 64) / (29 * 16))
number_row("P1-eq14", math.acos(1 - 1 / (0.463 * 16)), eq14_claimed, 1e-9, rel=1e-12, worded=True)


# ---- the brute-force maxima (tests/indep.c) over paper 1's and paper 2's ranges.
def brute(lo, hi, *specs):
    out = subprocess.run([indep, "maxima", str(lo), str(hi)] + list(specs), check=True, capture_output=True,
                         text=True).stdout
    return {d["spec"]: d for d in json.loads(out)}


p1 = brute(16, 1000, "fvol", "cq2", "schlick")
p2 = brute(2, 1000, "fq:0.64", "fq2", "cq2")
for d in list(p1.values()) + list(p2.values()):
    d["whole"] = max(d["att_max_abs"], d["epi_max_abs"])

number_row("P1-fig3-fvol", p1["fvol"]["max_rel"], 0.019, 0.001)
lower = sum(1 for f, q, s in zip(p1["fvol"]["per_n"], p1["cq2"]["per_n"], p1["schlick"]["per_n"])
            if f["rel"] < q["rel"] and f["rel"] < s["rel"])
relation_row("P1-fig3-order", lower == len(p1["fvol"]["per_n"]),
             "fvol's max delta below cq2's and schlick's at %d of %d n" % (lower, len(p1["fvol"]["per_n"])))
r = rows.get("P1-fig3-order")
if r and ("lower at %d of %d n" % (lower, len(p1["fvol"]["per_n"]))) not in r["measured_text"]:
    fail("P1-fig3-order", "measured text %r lacks 'lower at %d of %d n'" % (r["measured_text"], lower,
                                                                            len(p1["fvol"]["per_n"])))
# "4.5 times": the ratio of the two range maxima.
number_row("P1-4.5x", p1["cq2"]["max_rel"] / p1["fvol"]["max_rel"], 4.5, 0.1)
# figs. 5-6: at every n the attenuation zone's max Delta exceeds the epicentre's.
zone_ok = all(p["att"] > p["epi_abs"] for m in ("fvol", "cq2", "schlick") for p in p1[m]["per_n"])
relation_row("P1-fig5-zone", zone_ok, "attenuation max Delta above the epicentre's at every n")
relation_row("P1-fig5-order", p1["fvol"]["whole"] < p1["cq2"]["whole"] and p1["fvol"]["whole"] < p1["schlick"]["whole"],
             "fvol %g, cq2 %g, schlick %g" % (p1["fvol"]["whole"], p1["cq2"]["whole"], p1["schlick"]["whole"]))

# ---- paper 2 over n in [2, 1000].
number_row("P2-fq", p2["fq:0.64"]["max_rel"], 0.01255, 1e-5)
number_row("P2-fq2-rel", p2["fq2"]["max_rel"], 0.01256, 1e-5)
number_row("P2-fq2-abs", p2["fq2"]["whole"], 0.128, 0.001)
xe = math.acos(math.exp(-0.511 / p2["fq2"]["att_n"]))
relation_row("P2-fq2-zone", p2["fq2"]["att_max_abs"] >= p2["fq2"]["epi_max_abs"] and p2["fq2"]["att_x"] > xe,
             "fq2's max Delta at x = %g, x_e = %g" % (p2["fq2"]["att_x"], xe))
# f2's max delta: at the zone end of n = 1000 (closed form: 1 - (1 - n u/2)^2 / e^-0.511,
# u = 1 - e^(-0.511/n)), which the brute force must find as well.
u = -math.expm1(-0.511 / 1000)
f2 = 1 - (1 - 1000 * u / 2) ** 2 / math.exp(-0.511)
if abs(p2["cq2"]["max_rel"] - f2) > 1e-12:
    fail("P2-f2-rel", "brute force %r against the closed form %r" % (p2["cq2"]["max_rel"], f2))
number_row("P2-f2-rel", f2, 0.07924, 1e-5)
number_row("P2-f2-abs", p2["cq2"]["whole"], 0.162, 0.001)
number_row("P2-6.3x", f2 / p2["fq2"]["max_rel"], 6.3, 0.1)
relation_row("P2-fig3", p2["fq:0.64"]["whole"] < p2["cq2"]["whole"],
             "fq:Q=0.64 %g against f2 %g" % (p2["fq:0.64"]["whole"], p2["cq2"]["whole"]))


# ---- paper 2's fit of k_Q(n), Q = 0.64, over the integer n of [2, 1000].
def k_q(n, q=0.64):
    return (1 - math.sqrt(q)) / -math.expm1(math.log(q) / n)


ns = list(range(2, 1001))
# Fig. 4: at n = 2, k_Q = 1 exactly (Q^(1/2) = sqrt Q) and the fit is 0.995: |0.995 - 1| = 0.005
# exactly (worked by hand, in exact decimals); every other n must lie below it.
dev_at_2 = abs(Fraction("0.448") * 2 + Fraction("0.099") - 1)
others = max(abs((0.448 * n + 0.099) / k_q(n) - 1) for n in ns[1:])
fig4 = max(float(dev_at_2), others)
number_row("P2-fig4", fig4, 0.005, 0, absolute=1e-12, within=lambda v: dev_at_2 <= Fraction("0.005") and others < 0.005)


def least_squares(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return slope, my - slope * mx


ka, kb = least_squares(ns, [k_q(n) for n in ns])
number_row("P2-fit-k-a", ka, 0.448, 0.001)
number_row("P2-fit-k-b", kb, 0.099, 0.001)

# ---- figs. 2-3: the Q that minimises f_Q's max delta, by golden section in tests/indep.c.
best = json.loads(subprocess.run([indep, "bestq", "2", "1000"], check=True, capture_output=True, text=True).stdout)
number_row("P2-fig2-Q", best["Q"], 0.64, 0.005, absolute=1e-6)
number_row("P2-fig2-0.6", best["Q"], 0.6, 0.1, absolute=1e-6)


# ---- normalisation: coef(n) = 1/(2 pi I), I = int_0^min(1, 1/k) (1 - k t)^2 (1 - t) dt with
# t = 1 - u, k = 0.448n + 0.099: 1/2 - k/3 + k^2/12 for k <= 1, 1/(3k) - 1/(12k^2) for k >= 1.
def coef(n):
    k = 0.448 * n + 0.099
    i = 0.5 - k / 3 + k * k / 12 if k <= 1 else 1 / (3 * k) - 1 / (12 * k * k)
    return 1 / (2 * math.pi * i)


number_row("P2-coef-2", coef(2), 0.634, 0.001)
number_row("P2-coef-3", coef(3), 0.833, 0.001)
number_row("P2-coef-4", coef(4), 1.04, 0.01)
number_row("P2-coef-10", coef(10), 2.313, 0.001)
ca, cb = least_squares(ns, [coef(n) for n in ns])       # coef = a n + a b
number_row("P2-coef-fit-a", ca, 0.214, 0.001)
number_row("P2-coef-fit-b", cb / ca, 0.807, 0.001)
dev = max(abs(0.214 * (0.807 + n) / coef(n) - 1) for n in ns)
number_row("P2-coef-dev", dev, 0.053, 0.001)
# energy: the normal-incidence albedo of fq2n is 0.214 (0.807 + n) / coef(n); claimed <= 1.
alb = max(0.214 * (0.807 + n) / coef(n) for n in ns)
number_row("P2-energy", alb, 1, 0, within=lambda v: v <= 1 + 1e-9)

# ---- the harness's own checks: the device's albedo table at normal incidence (energy.json)
# against closed forms written here.
closed = {
    ("fq2n", "lobe"): lambda n: 0.214 * (0.807 + n) / coef(n),
    ("phongn", "lobe"): lambda n: 1.0,                        # (n+2)/(2 pi) 2 pi int u^(n+1) du
    ("blinnn", "lobe"): lambda n: 1.0,                        # Giesen's factor is the inverse integral
    ("beckmann", "D /"): lambda n: -math.expm1(-(n + 2) / 2),  # 1 - exp(-1/alpha^2)
    ("beckmann", "D cos"): lambda n: 1.0,                     # a microfacet D's projected area
    ("ggx", "D /"): lambda n: (n + 2) / (n + 4),              # tan^2(pi/4)/(alpha^2 + tan^2(pi/4))
    ("ggx", "D cos"): lambda n: 1.0,
}
row_of = {("fq2n", "lobe"): "C-albedo-fq2n", ("phongn", "lobe"): "C-albedo-phongn",
          ("blinnn", "lobe"): "C-albedo-blinnn", ("beckmann", "D /"): "C-albedo-beckmann",
          ("beckmann", "D cos"): "C-albedo-beckmann-norm", ("ggx", "D /"): "C-albedo-ggx",
          ("ggx", "D cos"): "C-albedo-ggx-norm"}
alb_tab = energy["albedo"]
i0 = alb_tab["theta_i_deg"].index(0)
seen = set()
for m in alb_tab["models"]:
    key = next((k for k in closed if k[0] == m["model"] and m["integrand"].startswith(k[1])), None)
    if key is None:
        continue
    seen.add(key)
    worst = max(abs(m["albedo"][j][i0] - closed[key](n)) for j, n in enumerate(alb_tab["n"]))
    number_row(row_of[key], worst, None, 0, absolute=1e-12, within=lambda v: v <= 2e-5)
for key, rid in row_of.items():
    if key not in seen:
        row(rid)
        fail(rid, "energy.json has no albedo table for %s (%s)" % key)

# Reciprocity: the verdict from energy.json's figures under the row's stated bounds.
rp = energy["reciprocity_image_pass"]["models"]
dev_worst = max(m["device_max_rel_diff"] for m in rp)
host_worst = max(m["host_max_rel_diff"] for m in rp)
lobe_worst = max(m["host_worst"]["max_diff_of_peak"] for m in energy["reciprocity"]["models"])
number_row("P2-reciprocity", dev_worst, None, 0, rel=1e-12,
           within=lambda v: v <= 1e-5 and host_worst <= 1e-9 and lobe_worst <= 1e-9)

# Host-vs-device quadrature and the grid-refinement check: the stated bounds. (That the device
# quadrature matches the closed forms to 1e-6 is test_reproduce.c's check.)
r = row("C-eq11-device")
if r:
    relation_row("C-eq11-device", r["measured"] is not None and 0 <= r["measured"] <= 1e-6, "bound 1e-6")
r = row("C-grid")
if r:
    relation_row("C-grid", r["measured"] is not None and 0 <= r["measured"] < 0.5, "bound 0.5 unit")

# fit: the per-n minimax k at n = 2 is 1 (cq2 = c^2 = c^n there, delta 0): worked by hand.
number_row("C-fit-k2", 1.0, 1, 1e-9, absolute=1e-9)

# Beaudoin and Guardado's table (m = 2, n = 18): A balances the largest f - c^n and c^n - f over
# c in [0, 1], f = max(0, A c + 1 - A)^2; bisection on A here over a grid of 4001 cosines dense
# near c = 1 (c = 1 - t^3), refined by a golden-section search around each side's best sample.
def bg_sides(a, n=18.0):
    def g(c):
        b = max(a * c + 1 - a, 0.0)
        return b * b - c ** n
    pts = [1 - (1 - i / 4000.0) ** 3 for i in range(4001)]
    out = []
    for sign in (1, -1):
        j = max(range(4001), key=lambda i: sign * g(pts[i]))
        lo, hi = pts[max(j - 1, 0)], pts[min(j + 1, 4000)]
        for _ in range(80):
            m1, m2 = lo + (hi - lo) * 0.382, lo + (hi - lo) * 0.618
            if sign * g(m1) < sign * g(m2):
                lo = m1
            else:
                hi = m2
        out.append(max(sign * g(pts[j]), sign * g(0.5 * (lo + hi))))
    return out


lo_a, hi_a = 0.0, 18.0
for _ in range(45):
    mid = 0.5 * (lo_a + hi_a)
    over, under = bg_sides(mid)
    if over > under:
        lo_a = mid
    else:
        hi_a = mid
bg_a = 0.5 * (lo_a + hi_a)
bg_err = max(bg_sides(bg_a))
number_row("BG-A-18", bg_a, 6.645, 0.001, absolute=1e-5)
number_row("BG-err-18", bg_err, 0.0631, 0.0001, absolute=1e-6)
# The cost argument (P1/P2-physical-cost): each physically based row against fq2 and Phong by
# compare's rule on the repetitions normalised by pow() in each round (physical.json). Here: the
# ratios recomputed as the Hodges-Lehmann estimate (the median of the pairwise differences of
# the logarithms, exponentiated), a "slower"/"faster" verdict only beyond the 10% minimum effect
# on that side of 1, and the row's verdict from the pairs' (every pair slower: reproduced; one
# faster or the same: not reproduced; otherwise within noise).
def hl_ratio(x, y):
    d = sorted(math.log(a) - math.log(b) for a in x for b in y if a > 0 and b > 0)
    m = len(d)
    return math.exp(d[m // 2] if m % 2 else 0.5 * (d[m // 2 - 1] + d[m // 2]))


try:
    phys = json.load(open(run + "/physical.json"), parse_constant=no_const)
except OSError:
    phys = None
for rid in ("P1-physical-cost", "P2-physical-cost"):
    r = row(rid)
    if r is None:
        continue
    if phys is None:
        fail(rid, "physical.json missing")
        continue
    prow = {x["model"]: x for x in phys["cost"]["rows"]}
    pb = [x for x in phys["cost"]["rows"] if x["physically_based"]]
    verdicts = []
    for x in pb:
        for key, other in (("vs_fq2", "fq2"), ("vs_phong", "phong")):
            ratio = hl_ratio(x["normalised_reps"], prow[other]["normalised_reps"])
            v = x[key]["verdict"]
            if abs(ratio - x[key]["ratio"]) > 1e-9 * ratio:
                fail(rid, "%s %s: ratio %r, the Hodges-Lehmann estimate here %r" % (x["model"], key, x[key]["ratio"], ratio))
            if (v == "slower" and not ratio < 1 / 1.1) or (v == "faster" and not ratio > 1.1):
                fail(rid, "%s %s: verdict %r at ratio %.4g (minimum effect 10%%)" % (x["model"], key, v, ratio))
            verdicts.append(v)
    worst_fq2 = max(x["ratio_to_fq2"] for x in pb)
    if not pb or abs(worst_fq2 - r["measured"]) > 1e-9 * worst_fq2:
        fail(rid, "measured %r, the fastest physically based model is %r x fq2" % (r["measured"], worst_fq2))
    expect = ("reproduced" if all(v == "slower" for v in verdicts)
              else "not reproduced" if any(v in ("faster", "same") for v in verdicts) else "within noise")
    if r["verdict"] != expect:
        fail(rid, "verdict %r, expected %r from the pairs' verdicts %s" % (r["verdict"], expect, verdicts))

# ---- every row checked, the summary counts the verdicts.
unchecked = sorted(set(rows) - checked)
if unchecked:
    failures.append("rows with no independent check here: " + ", ".join(unchecked))
s = claims["summary"]
rep = sum(1 for r in claims["claims"] if r["verdict"] == "reproduced")
noise = sum(1 for r in claims["claims"] if r["verdict"] == "within noise")
if s["reproduced"] != rep or s["not_reproduced"] != len(rows) - rep - noise or s.get("within_noise", 0) != noise \
        or s["rows"] != len(rows):
    failures.append("summary %r does not count the rows' verdicts (%d reproduced of %d)" % (s, rep, len(rows)))
for f in failures:
    print("FAIL:", f)
print("%d rows checked, %d failures" % (len(checked), len(failures)))
sys.exit(1 if failures else 0)
