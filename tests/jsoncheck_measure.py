"""jsoncheck_measure.py - the named checks of the measuring commands' outputs (accuracy,
throughput, render, frontier, fit, measured, gate, user models), for tests/jsoncheck.py. Each
is the assertions of one place of a shell test (named in its docstring)."""
import json
import math
import os
import sys

from jsoncheck_lib import check, has_context, load, load_result, no_const, read_csv  # noqa: F401

# ---- test_render_cli.sh ------------------------------------------------------------------------

@check
def render_cli_render_contract(*args):
    """check_json of test_render_cli.sh: render.json contract"""
    import os
    argv = ["check_json", *args]
    d, _ = load_result(argv[1], "brdfbench.render/3",
                       ("date", "device", "platform_version", "build_options", "git_revision"))
    scenes = {s["scene"]: s for s in d["scenes"]}
    assert sorted(scenes) == ["spheres", "teapot"], sorted(scenes)
    for s in scenes.values():
        assert [m["model"] for m in s["models"]] == ["phong", "blinn", "cq2", "fq2"]
        for m in s["models"]:
            assert m["double_reference_check"]["within_bound"] is True, m
            for f in m["files"].values():
                assert os.path.getsize(os.path.join(argv[2], f)) > 0, f
            # the signed error image beside the absolute one, named after it
            fs = m["files"]
            assert set(fs) == {"image", "error_image", "signed_error_image", "contact_sheet"}, fs
            assert fs["signed_error_image"] == fs["error_image"][:-len("_error.png")] + "_signed_error.png", fs
            # a model that is its own reference has no error at all
            if m["model"] == m["reference"]:
                assert m["metrics"]["max_abs"] == 0 and m["metrics"]["psnr_db"] is None
        (t,) = s["timings"]
        assert (t["width"], t["height"]) == (128, 64)
        cp = t["copy"]
        assert abs(cp["mpixel_per_s"] - 128 * 64 / (cp["median_ms"] * 1e3)) <= 1e-9 * cp["mpixel_per_s"], cp
        names = {e["name"]: e for e in t["entries"]}
        assert set(names) == {"phong", "blinn", "cq2", "fq2"}, names
        for e in names.values():
            assert 0 < e["min_ms"] <= e["median_ms"] <= e["max_ms"], e
            # Mpixel/s is the image's pixels over the median time (128 x 64 here)
            assert abs(e["mpixel_per_s"] - 128 * 64 / (e["median_ms"] * 1e3)) <= 1e-9 * e["mpixel_per_s"], e
            # each of the --reps 3 timed launches' rate: the slowest is the longest time, the
            # middle one is the median's
            reps = sorted(e["mpixel_per_s_reps"])
            assert len(reps) == 3, e
            assert abs(reps[0] - 128 * 64 / (e["max_ms"] * 1e3)) <= 1e-9 * reps[0], e
            assert abs(reps[1] - e["mpixel_per_s"]) <= 1e-9 * reps[1], e
            assert abs(reps[2] - 128 * 64 / (e["min_ms"] * 1e3)) <= 1e-9 * reps[2], e
            # the ratio is the interleaved copy's median over this entry's median
            assert abs(e["fraction_of_copy"] - e["copy_median_ms_interleaved"] / e["median_ms"]) < 1e-9
            # the speed-up is the reference's median time over this entry's (docs/definitions.md: cq2 and fq2 against
            # phong; a reference entry has none other than itself)
            r = names[e["reference"]]
            assert abs(e["speedup_vs_reference"] - r["median_ms"] / e["median_ms"]) <= 1e-9 * e["speedup_vs_reference"], e
        assert names["cq2"]["reference"] == "phong" and names["fq2"]["reference"] == "phong"
        assert names["blinn"]["reference"] == "blinn"


# ---- test_accuracy_pictures.sh -----------------------------------------------------------------

@check
def accuracy_pictures_z_beside_fq2(*args):
    """check_json of test_accuracy_pictures.sh: z is measured beside fq2"""
    argv = ["check_json", *args]
    d = load(argv[1])
    labels = [x["label"] for x in d["results"]]
    assert labels == ["fq2", "z"], labels
    z = d["results"][1]
    assert abs(z["epicentre"]["max_rel"] - 0.5) < 1e-12, z["epicentre"]


@check
def accuracy_pictures_field_z_closed_form(*args):
    """check_json of test_accuracy_pictures.sh: the field of z = 0.5 c^n has its closed-form peaks"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert d["model"] == "z" and d["reference"] == "phong", (d["model"], d["reference"])
    assert d["formula"] == "0.5*pow(c, n)" and d["lobe"] == "psi", (d["formula"], d["lobe"])
    assert abs(d["epicentre_max_rel"]["value"] - 0.5) < 1e-6, d["epicentre_max_rel"]
    assert abs(d["attenuation_max_abs"]["value"] - 0.5 * math.exp(-0.511)) < 1e-6, d["attenuation_max_abs"]
    assert d["grid"]["n_min"] == 2 and d["grid"]["n_max"] == 50, d["grid"]


@check
def accuracy_pictures_both_models_both_plots(*args):
    """check_json of test_accuracy_pictures.sh: both models in both plots"""
    argv = ["check_json", *args]
    d = load(argv[1])
    figs = {f["file"]: f for f in d["figures"]}
    for name in ("max_rel_error_epicentre_vs_n.png", "max_abs_error_vs_n.png"):
        labels = [s["label"] for s in figs[name]["series"]]
        assert "z" in labels and "fq2" in labels, (name, labels)
    z = [s for s in figs["max_rel_error_epicentre_vs_n.png"]["series"] if s["label"] == "z"][0]
    assert all(abs(v - 0.5) < 1e-6 for v in z["y"]), z["y"][:5]   # per-n figures plotted in float


# ---- test_report_cli.sh ------------------------------------------------------------------------

@check
def report_cli_frontier_all_models(*args):
    """check_json of test_report_cli.sh: the frontier of all --models"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert [m["model"] for m in d["models"]] == ["phong", "fvol", "cq2", "fq:Q=0.64"], [m["model"] for m in d["models"]]


# ---- test_measured_cli.sh ----------------------------------------------------------------------

@check
def measured_cli_measured(*args):
    """check_json of test_measured_cli.sh: measured.json"""
    argv = ["check_json", *args]
    d, _ = load_result(argv[1], "brdfbench.measured/2", ["date", "device", "git_revision", "grid"])
    m = d["materials"][0]
    assert m["name"] == "blinn64", m["name"]
    assert m["unmeasured_cells"] == 32400 and m["negative_cells_rgb"] == [0, 32400, 0], m["negative_cells_rgb"]
    assert m["used_cells"] + m["below_horizon_cells"] + m["unmeasured_cells"] == 1458000
    assert m["fit_cells"] <= 5000
    bp = m["blinn_phong"]
    for key, want in (("n", 64), ("ks", 2.5), ("kd", 0.08)):
        assert abs(bp[key] / want - 1) < 1e-3, (key, bp[key])
    # the material is the Blinn-Phong lobe: each lobe's error against it is its error against the fit
    for l in m["lobes"]:
        assert abs(l["err_measured"] - l["err_phong"]) <= 1e-9 * max(l["err_phong"], 1e-300), l
    assert m["device_check"]["status"] == "ok", m["device_check"]
    assert len(m["slices"]["theta_d"]) == 3 and len(m["slices"]["theta_h_deg"]) == 90


# ---- test_device_check.sh ----------------------------------------------------------------------

@check
def device_check_user_model_at_large_n(*args):
    """test_device_check.sh: user model at large n: the polished maxima miss the brute force"""
    import csv, math, sys
    argv = ["-", *args]
    rows = list(csv.DictReader(open(argv[1])))
    assert len(rows) == 2, rows
    for row in rows:
        n = float(row["n"]); se = -math.expm1(-0.511 / n); k = float.fromhex("0x1.cac084p-2") * n   # 0.448f
        best = max(abs(max(1 - k * s, 0) ** 2 - math.exp(n * math.log1p(-s))) / math.exp(n * math.log1p(-s))
                   for s in (se * i / 200000 for i in range(200001)))
        got, x = float(row["epicentre_max_rel_fraction"]), float(row["epicentre_at_x_rad"])
        unit = 10 ** (math.floor(math.log10(best)) - 3)
        print(n, got, best, x, 2 * math.asin(math.sqrt(se / 2)))
        assert abs(got - best) <= 0.1 * unit, (n, got, best)
        assert x <= 2 * math.asin(math.sqrt(se / 2)) * (1 + 1e-12), (n, x)


# ---- test_frontier_cli.sh ----------------------------------------------------------------------

@check
def frontier_cli_fit_contract_or_fit_worse(*args):
    """test_frontier_cli.sh: fit.json contract, or the fit is worse than pow4fit"""
    import json, sys
    argv = ["-", *args]
    t = argv[1]
    f = load(t + "/fit/fit.json")
    assert f["schema"] == "brdfbench.fit_family/2"
    assert f["family"] == "pow4" and f["objective"] == "max_rel"
    assert f["fit"]["status"] == "ok"
    assert f["model"].startswith("pow4:a=")
    a = load(t + "/acc/accuracy.json")
    frozen = [r for r in a["results"] if r["model"] == "pow4fit"][0]["epicentre"]["max_rel"]
    assert f["fit"]["max_rel"] <= frozen * (1 + 1e-3), (f["fit"]["max_rel"], frozen)
    assert f["device"]["max_rel"] <= frozen * (1 + 1e-3), (f["device"]["max_rel"], frozen)
    # the trade-off runs from the least max delta to the least max Delta
    assert f["min_max_abs"]["max_abs"] <= f["min_max_rel"]["max_abs"]
    assert f["min_max_rel"]["max_rel"] <= f["min_max_abs"]["max_rel"]


@check
def frontier_cli_frontier_contract_bounds(*args):
    """test_frontier_cli.sh: frontier.json contract and bounds"""
    import json, sys
    argv = ["-", *args]
    d = argv[1]
    j = load(d + "/frontier.json")
    has_context(j, "brdfbench.frontier/3", ("date", "device", "git_revision"))
    m = {r["model"]: r for r in j["models"]}
    assert set(m) == {"phong", "fq2", "pow4fit"}
    p4, fq2 = m["pow4fit"]["n_2_1000"], m["fq2"]["n_2_1000"]
    assert p4["max_rel"] <= 0.0060 and p4["max_abs"] <= 0.075, p4
    assert p4["max_rel"] < fq2["max_rel"] and p4["max_abs"] < fq2["max_abs"], (p4, fq2)
    assert m["phong"]["on_front"] is True
    assert m["phong"]["kind"] == "reference" and m["fq2"]["kind"] == "paper" and m["pow4fit"]["kind"] == "tuned"
    for r in j["models"]:
        assert r["psnr_db"] is None and r["psnr_reason"] == "no image pass", r
        assert r["rate_uniform"]["median"] > 0 and r["rate_varying"]["median"] > 0, r
        assert r["n_16_1000"]["max_rel"] <= r["n_2_1000"]["max_rel"] * (1 + 1e-12)
    rows = open(d + "/frontier.csv").read().strip().split("\n")
    assert len(rows) == 4 and rows[0].startswith("model,"), rows


# ---- test_gate_papers.sh -----------------------------------------------------------------------

@check
def gate_papers_papers_result_files(*args):
    """test_gate_papers.sh: papers.json result files"""
    import json, sys, xml.etree.ElementTree as ET
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    assert d["summary"]["failed"] == 0 and d["summary"]["passed"] == d["summary"]["gates"]
    # Every gate there carries both bounds, and the claimed figure (where a paper gives one) is
    # reported beside the measured one, never used as a bound.
    for g in d["gates"]:
        assert g["min"] is not None and g["max"] is not None, g
        assert "note" in g
    root = ET.parse(argv[2]).getroot()
    assert root.get("failures") == "0" and root.get("tests") == str(d["summary"]["gates"])


@check
def gate_papers_papers_figures_against_independent_values(*args):
    """test_gate_papers.sh: papers.json figures against independent values"""
    import json, math, subprocess, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    indep = argv[2]
    def coef(n):    # paper 2: 1/(2 pi int_0^min(1,1/k) (1 - k t)^2 (1 - t) dt), k = 0.448n + 0.099, by hand
        k = 0.448 * n + 0.099
        return 1 / (2 * math.pi * (0.5 - k / 3 + k * k / 12 if k <= 1 else 1 / (3 * k) - 1 / (12 * k * k)))
    bad = []
    for g in d["gates"]:
        lo, hi = int(g["n_min"]), int(g["n_max"])
        assert g["n_step"] == 1, g
        if g["model"] == "fq2n":
            ns = range(lo, hi + 1)
            if g["metric"] == "energy.max_abs_dev":      # max |0.214 (0.807 + n) / coef(n) - 1|
                want, tol = max(abs(0.214 * (0.807 + n) / coef(n) - 1) for n in ns), 1e-9
            else:                                         # albedo at normal incidence, the largest
                want, tol = max(0.214 * (0.807 + n) / coef(n) for n in ns), 2e-5   # device quadrature's bound
        else:
            spec = g["label"].replace("Q=", "").replace("k=", "")
            b = json.loads(subprocess.run([indep, "maxima", str(lo), str(hi), spec], check=True, capture_output=True,
                                          text=True).stdout)[0]
            want = b["max_rel"] if g["metric"] == "epicentre.max_rel" else b["att_max_abs"]
            want_n = b["max_rel_n"] if g["metric"] == "epicentre.max_rel" else b["att_n"]
            tol = 1e-9 * want
            if g["at_n"] != want_n:
                bad.append("%s: at n = %s, brute force %s" % (g["name"], g["at_n"], want_n))
        if abs(g["measured"] - want) > tol:
            bad.append("%s: measured %r, derived here %r" % (g["name"], g["measured"], want))
        if not (g["min"] <= want <= g["max"]):
            bad.append("%s: the pinned bounds [%r, %r] exclude the derived %r" % (g["name"], g["min"], g["max"], want))
    for b in bad:
        print("FAIL:", b)
    assert not bad and len(d["gates"]) == 16, len(d["gates"])


# ---- test_cli_accuracy.sh ----------------------------------------------------------------------

@check
def cli_accuracy_accuracy_contract(*args):
    """check_json of test_cli_accuracy.sh: accuracy.json contract"""
    import subprocess
    import math
    argv = ["check_json", *args]
    d, ctx = load_result(argv[1], "brdfbench.accuracy/3",
                         ("date", "device", "platform_version", "build_options", "git_revision", "grid"))
    assert ctx["grid"]["n_min"] == 2 and ctx["grid"]["n_max"] == 50 and ctx["grid"]["samples_per_zone"] == 256
    res = d["results"]
    assert [r["model"] for r in res] == ["cq2", "fq", "lyon"]
    assert res[1]["params"] == {"Q": 0.64} and res[2]["params"] == {"k": 3}
    # Each figure against tests/indep.c's brute force (grid + golden section over both zones of
    # every n, from the formulas written a second time in tests/lobe_formulas.h), with its n.
    out = subprocess.run([argv[2], "maxima", "2", "50", "cq2", "fq:0.64", "lyon:3"], check=True,
                         capture_output=True, text=True).stdout
    for r, b in zip(res, json.loads(out)):
        assert r["n_min"] == 2 and r["n_max"] == 50
        whole = max(b["att_max_abs"], b["epi_max_abs"])
        for zone, metric, want in (("epicentre", "max_rel", b["max_rel"]), ("attenuation", "max_abs", b["att_max_abs"]),
                                   ("whole", "max_abs", whole)):
            z = r[zone]
            assert abs(z[metric] - want) <= 1e-7 * want, (r["model"], zone, z, want)
            assert 2 <= z["at_n"] <= 50 and 0 <= z["at_x"] <= 1.5707963267948966 + 1e-12
        assert r["epicentre"]["at_n"] == b["max_rel_n"] and r["attenuation"]["at_n"] == b["att_n"], (r, b)
        # The device's grid samples the same function: never above the polished maximum beyond
        # float rounding (1e-5 relative).
        for zone, metric in (("epicentre", "max_rel"), ("attenuation", "max_abs"), ("whole", "max_abs")):
            assert r[zone]["grid_" + metric] <= r[zone][metric] * (1 + 1e-5), (r["model"], zone, r[zone])
        # The whole range's max |error| is the larger of the two zones' (zones partition [0, pi/2]).
        assert r["whole"]["max_abs"] >= r["attenuation"]["max_abs"]
        assert r["check"]["in_4th_digit_units"] < 0.05
    # Both ends of the epicentre are grid points (README: x uniform over [0, x_e(n)], both ends
    # included). cq2's and lyon:k=3's delta grows up to the zone's end (the brute force puts their
    # maxima at x_e(n)), so there the grid holds the maximum itself, to float rounding.
    for r, b in zip(res, json.loads(out)):
        xe = math.acos(math.exp(-0.511 / b["max_rel_n"]))
        if abs(b["max_rel_x"] - xe) < 1e-9 * xe:
            e = r["epicentre"]
            assert abs(e["grid_max_rel"] - e["max_rel"]) <= 1e-5 * e["max_rel"], (r["model"], e)
            assert abs(e["at_x"] - xe) <= 1e-9, (r["model"], e, xe)
    assert sum(1 for b in json.loads(out) if abs(b["max_rel_x"] - math.acos(math.exp(-0.511 / b["max_rel_n"]))) < 1e-9) == 2
    # cq2 at n = 50: its epicentre maximum is at the zone end (closed form: see test_accuracy.c);
    # the range maximum is at the largest n, where x_e = acos(exp(-0.511/50)).
    u = -math.expm1(-0.511 / 50)
    expect = 1 - (1 - 50 * u / 2) ** 2 / math.exp(-0.511)
    assert abs(res[0]["epicentre"]["max_rel"] - expect) < 1e-12, (res[0]["epicentre"], expect)
    assert res[0]["epicentre"]["at_n"] == 50


@check
def cli_accuracy_invalid_values_folded_into_maxima(*args):
    """test_cli_accuracy.sh: invalid values folded into maxima"""
    import json, math, sys
    argv = ["-", *args]
    r = json.load(open(argv[1]))["results"][0]
    assert r["status"] == "invalid_values" and r["invalid"]["count"] > 0, r
    # the first invalid point lies past c = 0.5, i.e. x > pi/3
    assert r["invalid"]["at_x"] > math.pi / 3 - 1e-6, r["invalid"]
    assert r["attenuation"]["max_abs"] < 1e-6 and r["whole"]["max_abs"] < 1e-6, r


# ---- test_throughput_cli.sh --------------------------------------------------------------------

@check
def throughput_cli_throughput_contract(*args):
    """check_json of test_throughput_cli.sh: throughput.json contract"""
    argv = ["check_json", *args]
    d, ctx = load_result(argv[1], "brdfbench.throughput/5",
                         ("date", "device", "platform_version", "build_options", "git_revision", "throughput"))
    assert ctx["throughput"]["reps"] == 2 and ctx["throughput"]["work_items"] == 4
    # the recorded work-group size is the launch's: 1 on a CPU device (PoCL spreads groups over
    # threads), else the largest of 256, 128, 64, 32 dividing the launch (4 work-items: none, 0)
    cpu = "pthread" in ctx["device"] or "cpu" in ctx["device"].lower() or "llvmpipe" in ctx["device"]
    assert ctx["throughput"]["local_size"] == (1 if cpu else 0), ctx["throughput"]
    assert [b["variant"] for b in d["builds"]] == ["default", "denorms-are-zero"]
    pk = d["peak"]
    # an FMA is 2 flops (kernels/peak.cl counts 2 flops per lane and step)
    assert pk["status"] == "ok" and abs(pk["fma_per_s"] - pk["flops_per_s"]["median"] / 2) <= 1e-9 * pk["fma_per_s"], pk
    rows = d["results"]
    # The runner (host/core/runner.h): --reps 2 rounds, the peak kernel three times per round (at
    # the round's start, middle and end), its rates kept in round order; each row's normalised
    # rate of round k is its rate over the median of the peak's three rates of round k, recomputed
    # here from the two arrays.
    rn = ctx["throughput"]["runner"]
    assert rn["rounds"] == 2 and rn["launches"] > 0 and rn["preemption_retries"] >= 0, rn
    pr = pk["flops_per_s_reps"]
    assert len(pr) == 3 * 2, pr
    ref = [sorted(pr[3 * k:3 * k + 3])[1] for k in range(2)]
    for r in d["results"]:
        if r["status"] != "ok":
            continue
        assert len(r["normalised_reps"]) == 2, r["normalised_reps"]
        for k in range(2):
            x, y = r["normalised_reps"][k], r["evals_per_s_reps"][k] / ref[k]
            assert abs(x - y) <= 1e-12 * y, (r["label"], k, x, y)
        # a CPU device: the rates per CPU second too, and the CPU seconds of each repetition
        assert len(r["normalised_cpu_reps"]) == 2 and len(r["cpu_seconds_reps"]) == 2, r
        assert r["timer"] == "profiling events", r["timer"]
    # pow + 3 models; default: uniform and varying; denorms-are-zero: uniform
    assert len(rows) == 4 * 2 + 4, len(rows)
    assert [r["label"] for r in rows[:8:2]] == ["pow", "phong", "cq2", "fq:Q=0.7"], [r["label"] for r in rows]
    def med(r): return r["evals_per_s"]["median"]
    def same(r, label): return [x for x in rows if x["label"] == label and x["variant"] == r["variant"] and x["n_mode"] == r["n_mode"]][0]
    def close(x, y, what): assert x is not None and abs(x - y) <= 1e-9 * abs(y), "%s: %r vs %r recomputed" % (what, x, y)
    # The derived columns, recomputed from the medians (README's definitions): the ratio to pow() in
    # the same variant and n mode, to the model's own reference (docs/definitions.md: the Phong lobe c^n for
    # every model here), to the tuned C loop's median, and the fraction of the FMA peak.
    for r in rows:
        assert r["status"] == "ok", r
        e = r["evals_per_s"]
        assert 0 < e["min"] <= e["median"] <= e["max"], e
        # every repetition is kept (--reps 2), and min/median/max are taken over them
        reps = sorted(r["evals_per_s_reps"])
        assert len(reps) == 2, reps
        assert math.isclose(reps[0], e["min"], rel_tol=1e-12) and math.isclose(reps[-1], e["max"], rel_tol=1e-12), (reps, e)
        # the median of rates is the rate of the median time: with 2 reps, work over the mean time (harmonic mean)
        assert math.isclose(e["median"], 2 / (1 / reps[0] + 1 / reps[1]), rel_tol=1e-9), (reps, e)
        if r["variant"] == "default":
            assert len(r["host_c"]["evals_per_s_reps"]) == 2, r["host_c"]
        close(r["ratio_to_reference"], med(r) / med(same(r, "pow")), r["label"] + " ratio_to_reference")
        close(r["fraction_of_peak"], med(r) / pk["fma_per_s"], r["label"] + " fraction_of_peak")
        if r["label"] != "pow":
            close(r["ratio_to_model_reference"], med(r) / med(same(r, "phong")), r["label"] + " ratio_to_model_reference")
        assert r["build_options"] == ("" if r["variant"] == "default" else "-cl-denorms-are-zero")
        assert r["accuracy"]["status"] == "ok" and r["accuracy"]["max_diff_of_peak"] < 1e-5
        if r["variant"] == "default":
            assert r["host_c"]["status"] == "ok", r
            close(r["ratio_to_host_c"], med(r) / r["host_c"]["evals_per_s"]["median"], r["label"] + " ratio_to_host_c")
    sw = d["sweep"]
    assert sw["status"] == "ok" and sw["n_count"] == 11, sw
    # the sweep's speed-up: tuned C's time over the device's, in total and per model
    close(sw["speedup_vs_host_c"], sw["host_c_seconds"] / sw["device_seconds"], "sweep speedup_vs_host_c")
    assert abs(sw["device_seconds"] - sum(m["device_seconds"]["median"] for m in sw["models"])) <= 1e-9 * sw["device_seconds"]
    assert abs(sw["host_c_seconds"] - sum(m["host_c_seconds"]["median"] for m in sw["models"])) <= 1e-9 * sw["host_c_seconds"]
    for m in sw["models"]:
        close(m["speedup_vs_host_c"], m["host_c_seconds"]["median"] / m["device_seconds"]["median"], m["label"] + " sweep speed-up")


@check
def throughput_cli_failed_variant_rows(*args):
    """test_throughput_cli.sh: failed variant rows"""
    import json, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    b = {x["variant"]: x for x in d["builds"]}
    assert b["default"]["status"] == "ok" and b["fast-relaxed-math"]["status"] == "failed", b
    for r in d["results"]:
        if r["variant"] == "fast-relaxed-math":
            assert r["status"] == "failed" and "build" in r["reason"] and r["evals_per_s"]["median"] is None, r
        else:
            assert r["status"] == "ok", r


@check
def throughput_cli_ab_options_two_sides(*args):
    """test_throughput_cli.sh: --ab-options: the two sides"""
    import json, sys
    argv = ["-", *args]
    full, a, b = (json.load(open(argv[1] + f)) for f in ("/throughput.json", "/ab/a/throughput.json", "/ab/b/throughput.json"))
    assert {r["variant"] for r in full["results"]} == {"default", "ab"}, {r["variant"] for r in full["results"]}
    key = lambda r: (r["label"], r["variant"], r["n_mode"])
    assert sorted(map(key, a["results"])) == sorted(map(key, b["results"])) and len(a["results"]) == 3 * 2
    assert all(len(r["normalised_cpu_reps"]) == 3 for r in a["results"] + b["results"])
    assert b["context"]["ab"]["side"] == "b" and "-cl-fast-relaxed-math" in b["context"]["build_options"]
    assert a["context"]["build_options"] == "" and a["peak"]["flops_per_s_reps"] == b["peak"]["flops_per_s_reps"]
    ab = {(r["label"], r["n_mode"]): r for r in full["results"] if r["variant"] == "ab"}
    for r in b["results"]:
        assert r["evals_per_s_reps"] == ab[(r["label"], r["n_mode"])]["evals_per_s_reps"]


# ---- test_fullbrdf_cli.sh ----------------------------------------------------------------------

@check
def fullbrdf_cli_bp_brdf_shaded_from_vectors(*args):
    """check_json of test_fullbrdf_cli.sh: render.json: bp.brdf shaded from the vectors, equal to blinn in float"""
    argv = ["check_json", *args]
    d = load(argv[1])
    sc = [s for s in d["scenes"] if s["scene"] == "teapot"][0]
    m = {x["model"]: x for x in sc["models"]}
    bp = m["bp"]
    assert bp["shading"] == "full-brdf", bp["shading"]
    assert bp["reference"] == "blinn", bp["reference"]
    # float against float: a few units of 2^-24 of the peak (identical in exact arithmetic)
    peak = bp["metrics"]["peak_reference"]
    assert peak > 0.1, peak
    assert bp["metrics"]["max_abs"] <= 1e-4 * peak, (bp["metrics"]["max_abs"], peak)
    assert bp["double_reference_check"]["max_abs_specular_difference"] <= 1e-3 * peak, bp["double_reference_check"]


@check
def fullbrdf_cli_physical_user_measured_rows(*args):
    """check_json of test_fullbrdf_cli.sh: physical.json: the user and measured rows"""
    argv = ["check_json", *args]
    d = load(argv[1])
    rows = {r["model"]: r for r in d["cost"]["rows"]}
    for name, kind in (("bp", "user BRDF (N, L, V)"), ("merl:b64", "table lookup")):
        r = rows[name]
        assert r["evaluates"] == kind, (name, r["evaluates"])
        assert r["status"] == "ok", (name, r["status"], r["check_max_abs_of_peak"])
        assert r["evaluations_per_s"] is not None and math.isfinite(r["evaluations_per_s"]) \
            and r["evaluations_per_s"] > 0, (name, r["evaluations_per_s"])
    for r in rows.values():
        assert r["status"] == "ok", (r["model"], r["check_max_abs_of_peak"])
    assert "memory bandwidth" in d["lookup_note"]


@check
def fullbrdf_cli_render_measured_material_beside_fits(*args):
    """check_json of test_fullbrdf_cli.sh: render.json: the measured material beside its fits"""
    argv = ["check_json", *args]
    d = load(argv[1])
    sc = [s for s in d["scenes"] if s["scene"] == "teapot"][0]
    m = sc["measured"][0]
    assert m["material"] == "b64" and m["check_status"] == "ok", m
    peak = m["peak_radiance"]
    assert peak > 0.5, peak
    fits = {f["fit"]: f for f in m["fits"]}
    assert sorted(fits) == ["blinn-phong fit", "ct-beckmann fit", "ct-ggx fit"], sorted(fits)
    b = fits["blinn-phong fit"]
    for key, want in (("n", 64), ("ks", 2.5), ("kd", 0.08)):
        assert abs(b[key] - want) <= 1e-3 * want, (key, b[key], want)
    assert b["rms"] <= 0.01 * peak and b["max_abs"] <= 0.1 * peak, (b["rms"], b["max_abs"], peak)


# ---- test_rusticl.sh ---------------------------------------------------------------------------

@check
def rusticl_figures_against_pocl(*args):
    """test_rusticl.sh: rusticl's figures against PoCL's"""
    import json, sys
    argv = ["-", *args]
    a, b = (json.load(open(p)) for p in argv[1:3])
    assert "llvmpipe" in b["context"]["device"], b["context"]["device"]
    assert len(a["results"]) == len(b["results"]) == 2
    for ra, rb in zip(a["results"], b["results"]):
        assert ra["label"] == rb["label"]
        if rb.get("status") == "device_disagrees":
            print("%s flagged device_disagrees on rusticl" % rb["label"])
            continue
        for zone in ("epicentre", "attenuation", "whole"):
            for k, x in ra[zone].items():
                y = rb[zone][k]
                if isinstance(x, float) and k.startswith("max"):
                    assert "%.3e" % x == "%.3e" % y, (ra["label"], zone, k, x, y)
        assert rb["timing"]["timer"] in ("profiling events", "wall time: the driver's profiling events gave no time")


@check
def rusticl_throughput_on_rusticl_every_row(*args):
    """check_json of test_rusticl.sh: throughput on rusticl: every row measured, the scalar kernels"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert "llvmpipe" in d["context"]["device"]
    assert all(r["status"] == "ok" for r in d["results"]), [r for r in d["results"] if r["status"] != "ok"]
    assert len(d["results"]) == 3 * 2
    assert "-DTP_W=1" in d["builds"][0]["build_options"], d["builds"]


@check
def rusticl_device_all_three_devices(*args):
    """check_json of test_rusticl.sh: --device all: three devices, each with its own context"""
    argv = ["check_json", *args]
    d = load(argv[1])
    devs = d["context"]["devices"]
    assert len(devs) == 3, devs
    assert any("llvmpipe" in x["device"] for x in devs) and any("basic" in x["device"] for x in devs), devs
    assert len({r["device"] for r in d["results"]}) == 3


@check
def rusticl_compare_three_drivers(*args):
    """check_json of test_rusticl.sh: compare lays the three drivers side by side"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert len(d["runs"]) == 3, [r["name"] for r in d["runs"]]


# ---- test_shaderlang_cli.sh --------------------------------------------------------------------

@check
def shaderlang_cli_five_writings_lyon_k2(*args):
    """check_json of test_shaderlang_cli.sh: the five writings have lyon:k=2's figures in accuracy.json"""
    argv = ["check_json", *args]
    d = load(argv[1])
    r = {x["label"]: x for x in d["results"]}
    ref = r["lyon:k=2"]
    for label in ("quartic_cl:k=0.25", "quartic_glsl:k=0.25", "quartic_hlsl:k=0.25", "q4"):
        x = r[label]
        assert x["status"] == "ok", x
        for zone, key in (("epicentre", "max_rel"), ("attenuation", "max_abs"), ("whole", "max_abs")):
            a, b = x[zone][key], ref[zone][key]
            assert abs(a - b) <= 1e-12 * abs(b), (label, zone, a, b)
            assert x[zone]["at_n"] == ref[zone]["at_n"], (label, zone)


@check
def shaderlang_cli_brdf_blinn_phong_cook_torrance(*args):
    """check_json of test_shaderlang_cli.sh: .brdf Blinn-Phong and Cook-Torrance are the built-in models

    Full BRDFs are measured over the hemisphere where N.L > 0 and N.V > 0 (docs/definitions.md):
    each file's formula is algebraically its reference's, so every figure is rounding (below
    1e-9), no sample is taken below the horizon, and the status is ok. (Measured as a lobe with
    L = N, the Blinn-Phong file used to show a max Delta of 0.5 at n = 2, x = pi/4: the reference
    there was not zeroed below the horizon, the BRDF was.)"""
    argv = ["check_json", *args]
    d = load(argv[1])
    r = {x["model"]: x for x in d["results"]}
    bp, ct, full = r["blinnphong"], r["ct_ggx"], r["ct_full"]
    assert bp["reference"] == "blinn", bp["reference"]
    assert ct["reference"] == "ct-ggx:F0=0.5" and full["reference"] == "ct-ggx:F0=0.5", (ct["reference"], full["reference"])
    for x in (bp, ct, full):
        assert x["sweep"] == "hemisphere" and x["status"] == "ok", (x["model"], x.get("sweep"), x["status"])
        h = x["hemisphere"]
        for zone, key in (("epicentre", "max_rel"), ("attenuation", "max_abs"), ("whole", "max_abs")):
            assert h[zone][key] < 1e-9, (x["model"], zone, h[zone])
        assert h["samples"]["evaluated_below_horizon"] == 0 and h["samples"]["used"] > 0, (x["model"], h["samples"])


@check
def shaderlang_cli_brdf_model_measured_by_throughput(*args):
    """check_json of test_shaderlang_cli.sh: the .brdf model measured by throughput"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert [x for x in d["results"] if x["model"] == "blinnphong"], [x["model"] for x in d["results"]]


# ---- test_usermodel.sh -------------------------------------------------------------------------

@check
def usermodel_closed_form_figures_k_c_n(*args):
    """check_json of test_usermodel.sh: closed-form figures of k c^n (k = 3 and 0.5)"""
    argv = ["check_json", *args]
    d = load(argv[1])
    r = {x["label"]: x for x in d["results"]}
    assert set(r) == {"scaled:k=3", "half"}, list(r)
    for label, k in (("scaled:k=3", 3.0), ("half", 0.5)):
        x = r[label]
        assert x["status"] == "ok", x
        assert x["reference"] == "phong"
        assert abs(x["epicentre"]["max_rel"] - abs(k - 1)) < 1e-12, x["epicentre"]
        assert abs(x["whole"]["max_abs"] - abs(k - 1)) < 1e-12, x["whole"]
        assert abs(x["whole"]["at_x"]) < 1e-9, x["whole"]
        assert abs(x["attenuation"]["max_abs"] - abs(k - 1) * math.exp(-0.511)) < 1e-12, x["attenuation"]
        # The double reference ran on the device: its check against the float sweep holds.
        assert x["check"]["in_4th_digit_units"] < 0.05, x["check"]
        assert x["check"]["probe_max_diff_of_peak"] < 1e-5, x["check"]
        assert "reason" not in x, x
    assert r["scaled:k=3"]["params"] == {"k": 3}


@check
def usermodel_myquad_cq2_closed_form(*args):
    """check_json of test_usermodel.sh: myquad:a=0.5,b=0 has cq2's closed-form maximum"""
    argv = ["check_json", *args]
    d = load(argv[1])
    x = d["results"][0]
    assert x["label"] == "myquad:a=0.5,b=0" and x["params"] == {"a": 0.5, "b": 0}, x
    u = -math.expm1(-0.511 / 50)
    expect = 1 - (1 - 50 * u / 2) ** 2 / math.exp(-0.511)
    assert abs(x["epicentre"]["max_rel"] - expect) < 1e-12, (x["epicentre"], expect)
    assert x["epicentre"]["at_n"] == 50


@check
def usermodel_only_user_model_runs(*args):
    """check_json of test_usermodel.sh: only the user model runs when no --models is given"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert [x["model"] for x in d["results"]] == ["cube"], d["results"]


@check
def usermodel_float_fallback_reported_accuracy(*args):
    """check_json of test_usermodel.sh: float fallback is reported in accuracy.json"""
    argv = ["check_json", *args]
    d = load(argv[1])
    x = d["results"][0]
    assert "no cl_khr_fp64" in x["reason"], x
    assert abs(x["epicentre"]["max_rel"] - 0.5) < 1e-6, x["epicentre"]


@check
def usermodel_nan_values_counted(*args):
    """check_json of test_usermodel.sh: NaN values are counted, with the first location"""
    argv = ["check_json", *args]
    d = load(argv[1])
    x = d["results"][0]
    S = 256
    expect, slack = 0, 0
    for n in range(2, 13):
        se = -math.expm1(-0.511 / n)
        for j in range(1, S + 1):
            sj = se * (1 / se) ** (j / S)
            if abs(sj - 0.5) < 1e-6: slack += 1
            elif sj > 0.5: expect += 1
    assert x["status"] == "invalid_values", x["status"]
    cnt = x["invalid"]["count"]
    assert expect <= cnt <= expect + slack, (cnt, expect, slack)
    assert x["invalid"]["at_n"] == 2 and x["invalid"]["at_x"] > math.pi / 3 - 1e-6, x["invalid"]
    assert str(cnt) in x["reason"] and "NaN, Inf or negative" in x["reason"], x["reason"]


@check
def usermodel_gates_on_closed_forms(*args):
    """check_json of test_usermodel.sh: user-model gates judged on closed forms"""
    argv = ["check_json", *args]
    d = load(argv[1])
    g = d["gates"]
    assert [x["status"] for x in g] == ["pass", "fail", "pass"], [(x["status"], x.get("reason")) for x in g]
    assert all(x["user_model"] for x in g)
    assert abs(g[0]["measured"] - 0.5) < 1e-12 and abs(g[1]["measured"] - 0.5) < 1e-12
    assert abs(g[2]["measured"] - 0.75) < 1e-12
    assert d["summary"]["sweeps"] == 2, d["summary"]


@check
def usermodel_render_k_c_n_identity(*args):
    """check_json of test_usermodel.sh: render of k c^n: identity figures"""
    argv = ["check_json", *args]
    d = load(argv[1])
    ms = {m["model"]: m for m in d["scenes"][0]["models"]}
    one, two = ms["scaled:k=1"], ms["scaled:k=2"]
    assert one["family"] == "user" and one["reference"] == "phong"
    assert one["metrics"]["max_abs"] == 0, one["metrics"]
    p = two["metrics"]["peak_reference"]
    assert p > 0 and abs(two["metrics"]["max_abs"] - p) <= 1e-6 * p, two["metrics"]
    assert one["double_reference_check"]["within_bound"] and two["double_reference_check"]["within_bound"]


@check
def usermodel_frontier_all_models_with_user(*args):
    """check_json of test_usermodel.sh: the frontier of all --models with a user model"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert [m["model"] for m in d["models"]] == ["fq2", "scaled:k=2"], [m["model"] for m in d["models"]]


@check
def usermodel_user_model_error_field(*args):
    """check_json of test_usermodel.sh: the user model's error field"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert d["model"] == "scaled:k=2" and d["reference"] == "phong"
    assert d["check"]["max_rel_diff"] < 1e-6, d["check"]
    # (2r - r) / r = 1 in every cell, and exactly so in float (2r and 2r - r are exact)
    cells = d["grid"]["rows"] * d["grid"]["cols"]
    assert len(d["epicentre_rel"]) == cells and all(v == 1 for v in d["epicentre_rel"]), d["epicentre_rel"][:8]


@check
def usermodel_user_model_measured_by_throughput(*args):
    """check_json of test_usermodel.sh: the user model measured by throughput"""
    argv = ["check_json", *args]
    d = load(argv[1])
    r = [x for x in d["results"] if x["model"] == "myquad"]
    assert len(r) == 1, [x["model"] for x in d["results"]]
    r = r[0]
    assert r["status"] == "ok", r
    # the ratio to pow() is this median over the median of the pow() row, measured in the same run
    p = [x for x in d["results"] if x["label"] == "pow" and x["n_mode"] == r["n_mode"] and x["variant"] == r["variant"]][0]
    assert abs(r["ratio_to_reference"] - r["evals_per_s"]["median"] / p["evals_per_s"]["median"]) <= 1e-9 * r["ratio_to_reference"], r
    assert r["accuracy"]["status"] == "ok" and r["accuracy"]["max_diff_of_peak"] < 1e-5, r["accuracy"]


@check
def usermodel_doc_example_figures(*args):
    """test_usermodel.sh: the doc's example gives other figures than the doc states"""
    import json, math, re, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    doc = open(argv[2]).read()
    sq, quad = d["results"]
    for zone, key in (("epicentre", "max_rel"), ("attenuation", "max_abs"), ("whole", "max_abs")):
        a, b = sq[zone], quad[zone]
        assert abs(a[key] - b[key]) <= 1e-12 * b[key] and a["at_n"] == b["at_n"], (zone, a, b)
    def f(c, n):
        b = max(0.45 * n * (c - 1) + 1, 0.0)
        return b * b
    def xe(n): return math.acos(math.exp(-0.511 / n))
    def maximum(g, lo, hi, steps=4000):
        xs = [lo + (hi - lo) * i / steps for i in range(steps + 1)]
        i = max(range(len(xs)), key=lambda k: g(xs[k]))
        a, b = xs[max(i - 1, 0)], xs[min(i + 1, steps)]
        r = (math.sqrt(5) - 1) / 2
        for _ in range(100):
            x1, x2 = b - r * (b - a), a + r * (b - a)
            if g(x1) > g(x2): b = x2
            else: a = x1
        return max(g(xs[i]), g((a + b) / 2))
    rel = lambda n: maximum(lambda x: abs(f(math.cos(x), n) / math.cos(x) ** n - 1), 0.0, xe(n))
    ab = lambda n: maximum(lambda x: abs(f(math.cos(x), n) - math.cos(x) ** n), xe(n), math.pi / 2, 40000)
    e, t = sq["epicentre"], sq["attenuation"]
    assert e["at_n"] == 16 and t["at_n"] == 1000, (e, t)
    assert abs(e["max_rel"] - rel(16)) < 1e-9, (e, rel(16))
    assert abs(t["max_abs"] - ab(1000)) < 1e-9, (t, ab(1000))
    # the maxima over n are where the run puts them (a sample of the grid)
    for n in (17, 20, 32, 64, 100, 250, 500, 999):
        assert rel(n) <= e["max_rel"] + 1e-12 and ab(n) <= t["max_abs"] + 1e-12, n
    # the doc states them to 4 significant digits
    m = re.search(r"max δ of ([0-9.]+)% in the epicentre \(at n = (\d+), x = ([0-9.]+) rad\) and a max Δ of\s+([0-9.]+) in the attenuation zone \(at n = (\d+), x = ([0-9.]+) rad\)", doc)
    assert m, "no figures in the doc"
    assert m.group(1) == "%.4g" % (100 * e["max_rel"]) and int(m.group(2)) == 16, (m.groups(), e)
    assert float(m.group(3)) == round(e["at_x"], 4), (m.groups(), e)
    assert m.group(4) == "%.4f" % t["max_abs"] and int(m.group(5)) == 1000, (m.groups(), t)
    assert float(m.group(6)) == round(t["at_x"], 4), (m.groups(), t)


@check
def usermodel_native_powr_exact_reference(*args):
    """check_json of test_usermodel.sh: native_powr is exact in the reference"""
    argv = ["check_json", *args]
    d = load(argv[1])
    x = d["results"][0]
    assert x["status"] == "ok", x
    assert x["epicentre"]["max_rel"] < 1e-13 and x["whole"]["max_abs"] < 1e-13, x
