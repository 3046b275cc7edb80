"""rows_layouts.py - the rows of throughput, accuracy, render, fit, frontier, claims, q_sweep,
physical, energy and measured result files written a second time, in Python, from each kind's own layout (the members docs/schemas/ describes), for
tests/test_rows_primary.sh: what the program reads from a file's "rows" member and from an old
file's layout (host/results/rdoc_read.c) is checked against this independent mapping.

expected(doc) -> {row label: {metric name: (unit, direction, timed, value, reps)}}; a value of
None stands for a figure not measured (null); each row's status and reason (None when ok) are
its entry STATUS."""
import json
import math
import sys


STATUS = "(status)"


def _status(obj, word="status"):
    """A row's status and reason from the layout's object: ("ok", None), or the word and its
    reason (the word itself when none is given)."""
    st = obj.get(word, "ok") if obj else "ok"
    return ("ok", None) if st == "ok" else (st, obj.get("reason") or st)


def _g(x):
    return "%g" % x


def _throughput(d):
    out = {}
    pk = d["peak"]
    f = pk["flops_per_s"]
    out["peak (reference kernel)"] = {"flops_per_s": ("FLOP/s", "higher", True, f["median"], pk["flops_per_s_reps"]),
                                      STATUS: _status(pk)}
    for r in d["results"]:
        label = "%s | %s | n %s" % (r["label"], r["variant"], r["n_mode"])
        out[label] = {"evals_per_s": ("1/s", "higher", True, r["evals_per_s"]["median"], r["evals_per_s_reps"]),
                      STATUS: _status(r)}
        # what the throughput page reads beside the rate: the tuned C loop's rate (timed with the
        # default build options), the accuracy against the double reference
        hc, acc = r.get("host_c", {}), r.get("accuracy", {})
        if r["variant"] == "default" and hc.get("status") == "ok":
            out[label]["host_c.evals_per_s"] = ("1/s", "higher", True, hc["evals_per_s"]["median"],
                                                hc["evals_per_s_reps"])
        if acc.get("status") == "ok":
            out[label]["accuracy.max_diff_of_peak"] = ("1", "neither", False, acc["max_diff_of_peak"], [])
        if acc.get("nonfinite", 0) > 0:
            out[label]["accuracy.nonfinite"] = ("1", "neither", False, acc["nonfinite"], [])
    # the accuracy sweep: a row per model, its points and each side's points per second
    sw = d.get("sweep", {})
    for m in sw.get("models", []) if sw.get("status", "not run") != "not run" else []:
        ok = m.get("status") == "ok"
        row = {"points": ("1", "neither", False, m["points"], []), STATUS: _status(m)}
        for side in ("device", "host_c"):
            row[side + "_points_per_s"] = ("1/s", "higher", True,
                                           m["points"] / m[side + "_seconds"]["median"] if ok else None, [])
        out["%s | accuracy sweep" % m["label"]] = row
    return out


def _render(d):
    out = {}
    for sc in d["scenes"]:
        size = "%s %sx%s" % (sc["scene"], _g(sc["image"]["width"]), _g(sc["image"]["height"]))
        for mo in sc["models"]:
            met = mo["metrics"]
            ok = met.get("status", "ok") == "ok"
            row = {STATUS: _status(met)}
            for name, unit, direction in (("max_abs", "1", "lower"), ("rmse", "1", "lower"), ("psnr_db", "dB", "higher"),
                                          ("share_above_threshold", "1", "lower")):
                if met[name] is not None or not ok:   # the PSNR of identical images is left out
                    row[name] = (unit, direction, False, met[name], [])
            out["%s | %s" % (size, mo["model"])] = row
        for tm in sc["timings"]:
            at = "@%sx%s" % (_g(tm["width"]), _g(tm["height"]))
            for en in tm["entries"]:
                key = "%s | %s" % (sc["scene"], en["name"])
                row = out.setdefault(key, {STATUS: ("ok", None)})
                row["mpixel_per_s" + at] = ("Mpixel/s", "higher", True, en["mpixel_per_s"], en["mpixel_per_s_reps"])
                # the share of the copy kernel's speed and the speed-up against the reference, as shown
                row["fraction_of_copy" + at] = ("1", "higher", False, en["fraction_of_copy"], [])
                if "speedup_vs_reference" in en:
                    row["speedup_vs_reference" + at] = ("1", "higher", False, en["speedup_vs_reference"], [])
        hc = sc.get("he_comparison")
        if hc:   # He's model: the Blinn-Phong fit to it, then each model shaded at that n against it
            out["%s | %s | Blinn-Phong fit" % (size, hc["model"])] = {
                "n_fit": ("1", "neither", False, hc["n_fit"], []), "k_fit": ("1", "neither", False, hc["k_fit"], []),
                "relative_rms_residual": ("1", "lower", False, hc["relative_rms_residual"], []), STATUS: ("ok", None)}
            for en in hc["entries"]:
                met = en["metrics"]
                ok = met.get("status", "ok") == "ok"
                row = {STATUS: _status(met)}
                for name, v in (("max_abs", met["max_abs"]), ("mean_abs", met["mean_abs"]),
                                ("max_abs_vs_blinn_fit", en["max_abs_vs_blinn_fit"])):
                    if v is not None or not ok:
                        row[name] = ("1", "lower", False, v, [])
                out["%s | %s | %s" % (size, hc["model"], en["name"])] = row
    return out


def _fit(d):
    g = d["context"]["grid"]
    grid = "n %s..%s step %s, %s samples per zone" % (_g(g["n_min"]), _g(g["n_max"]), _g(g["n_step"]),
                                                      _g(g["samples_per_zone"]))
    out = {}
    for role, obj in (("best affine k(n)", d), ("capped at fq2's max Delta", d["capped_at_fq2"])):
        out["%s | %s" % (role, grid)] = {
            "a": ("1", "neither", False, obj["a"], []), "b": ("1", "neither", False, obj["b"], []),
            "max_rel": ("1", "lower", False, obj["max_rel"], []), "max_abs": ("1", "lower", False, obj["max_abs"], []),
            STATUS: _status(obj)}
    # the family's limit: the largest per-n minimax max delta over the grid, and where
    lim = d["limit_overall"]
    out["per-n minimax k(n): the family's limit | %s" % grid[:120]] = {
        "max_rel": ("1", "lower", False, lim["max_rel"], []), "at_n": ("1", "neither", False, lim["at_n"], []),
        STATUS: ("ok", None)}
    for c in d["compare"]:
        if c["model"].startswith("quad:"):   # the fitted models themselves: their rows are above
            continue
        out["%s | %s" % (c["model"], grid)] = {"max_rel": ("1", "lower", False, c["max_rel"], []),
                                              "max_abs": ("1", "lower", False, c["max_abs"], []), STATUS: ("ok", None)}
    return out


def _frontier(d):
    """A row per model: its accuracy figures and PSNR, then what the page shows beside them: the
    median rates (their min and max are checked by test_rows_primary.sh) and the front, figures
    of direction neither."""
    out = {}
    for m in d["models"]:
        row = {STATUS: _status(m)}
        for rng in ("n_2_1000", "n_16_1000"):
            for fig in ("max_rel", "max_abs"):
                row["%s.%s" % (rng, fig)] = ("1", "lower", False, m[rng][fig], [])
        row["psnr_db"] = ("dB", "higher", False, m["psnr_db"], [])
        for mode in ("uniform", "varying"):
            row["evals_per_s_" + mode] = ("1/s", "neither", False, m["rate_" + mode]["median"], [])
        row["on_front"] = ("1", "neither", False, 1 if m["on_front"] else 0, [])
        out[m["model"]] = row
    return out


_STEM_KEEP = set("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-")


def _measured_stems(names):
    """Each material's picture stem: its name with every character outside [A-Za-z0-9._-] made
    '_', then -2, -3, ... when an earlier material has that stem (docs/measured.md)."""
    stems = []
    for name in names:
        base = "".join(chr(b) if chr(b) in _STEM_KEEP else "_" for b in name.encode())   # byte by byte, as C
        stem, k = base, 2
        while stem in stems:
            stem, k = "%s-%d" % (base, k), k + 1
        stems.append(stem)
    return stems


def _measured(d):
    """A row per material (its cell counts and device check), per fit (its parameters and RMS
    errors, failed when the fit did not converge or did not run) and per lobe (its errors against
    the material and the fitted Blinn-Phong, and their ratio), keyed by the material's stem."""
    def fig(v, direction="neither"):
        return ("1", direction, False, v, [])
    out = {}
    mats = d["materials"]
    for mat, stem in zip(mats, _measured_stems([m["name"] for m in mats])):
        dc = mat["device_check"]
        row = {STATUS: ("ok", None)}
        for name, v in (("cells", mat["cells"]), ("unmeasured_cells", mat["unmeasured_cells"]),
                        ("negative_cells.red", mat["negative_cells_rgb"][0]),
                        ("negative_cells.green", mat["negative_cells_rgb"][1]),
                        ("negative_cells.blue", mat["negative_cells_rgb"][2]),
                        ("below_horizon_cells", mat["below_horizon_cells"]), ("used_cells", mat["used_cells"]),
                        ("fit_cells", mat["fit_cells"]), ("device_check.points", dc["points"]),
                        ("device_check.same_cell", dc["same_cell"])):
            row[name] = fig(v)
        row["device_check.value_differs"] = fig(dc["value_differs"], "lower")
        out[stem] = row
        for member, name in (("blinn_phong", "blinn-phong"), ("ct_beckmann", "ct-beckmann"), ("ct_ggx", "ct-ggx")):
            f = mat[member]
            row = {STATUS: _status(f)}
            for p in (("n",) if member == "blinn_phong" else ("alpha", "n_of_alpha", "F0")):
                row[p] = fig(f[p])
            row["ks"] = ("1/sr", "neither", False, f["ks"], [])
            row["kd"] = ("1/sr", "neither", False, f["kd"], [])
            row["rms"] = fig(f["rms"], "lower")
            row["rms_fit_cells"] = fig(f["rms_fit_cells"], "lower")
            row["iterations"] = fig(f["iterations"])
            out["%s | fit %s" % (stem, name)] = row
        for lb in mat["lobes"]:
            out["%s | %s" % (stem, lb["model"])] = {
                "err_measured": fig(lb["err_measured"], "lower"), "err_phong": fig(lb["err_phong"], "lower"),
                "ratio": fig(lb["ratio"]), STATUS: ("ok", None)}
    return out


def _accuracy(d):
    """A row per result: a lobe sweep's (label | the run's grid) with its four figures, the
    device check's float cancellation where it is a number and the fp16 figures of code in half;
    a hemisphere sweep's (label | vs REF, hemisphere AXIS MIN..MAX xCOUNT, NHxNDxNP) with its
    hemisphere.* figures. Every figure an error: unit 1, lower is better, not timed."""
    g = d["context"].get("grid")
    grid = ("n %s..%s step %s, %s samples per zone" % (_g(g["n_min"]), _g(g["n_max"]), _g(g["n_step"]),
                                                       _g(g["samples_per_zone"]))) if g else ""

    def err(v):
        return ("1", "lower", False, v, [])
    out = {}
    for r in d["results"]:
        row = {STATUS: _status(r)}
        h = r.get("hemisphere")
        if h:
            ax, hg = h["axis"], h["grid"]
            key = "vs %s, hemisphere %s %.9g..%.9g x%.0f, %.0fx%.0fx%.0f" % (
                r["reference"][:60], ax["name"][:40], ax["min"], ax["max"], ax["count"], hg["theta_h"], hg["theta_d"],
                hg["phi_d"])
            for name, v in (("epicentre.max_rel", h["epicentre"]["max_rel"]),
                            ("attenuation.max_abs", h["attenuation"]["max_abs"]),
                            ("whole.max_abs", h["whole"]["max_abs"]), ("rms", h["rms"]),
                            ("float_cancellation", h["float_cancellation"]),
                            ("evaluated_below_horizon", h["samples"]["evaluated_below_horizon"])):
                row["hemisphere." + name] = err(v)
        else:
            key = grid
            row["epicentre.max_rel"] = err(r["epicentre"]["max_rel"])
            row["attenuation.max_abs"] = err(r["attenuation"]["max_abs"])
            row["whole.max_abs"] = err(r["whole"]["max_abs"])
            row["invalid.count"] = err(r["invalid"]["count"])
            fc = r["check"].get("float_cancellation")
            if isinstance(fc, (int, float)):
                row["check.float_cancellation"] = err(fc)
            if "fp16" in r:
                for name in ("max_rel", "max_abs", "invalid_count"):
                    row["fp16." + name] = err(r["fp16"][name])
            # where the maxima and the first invalid value lie (x in radians), and the device
            # check in units of the 4th significant digit
            for zone in ("epicentre", "attenuation", "invalid"):
                row[zone + ".at_n"] = ("1", "neither", False, r[zone]["at_n"], [])
                row[zone + ".at_x"] = ("rad", "neither", False, r[zone]["at_x"], [])
            row["check.in_4th_digit_units"] = ("4th-digit units", "lower", False, r["check"]["in_4th_digit_units"], [])
        out["%s | %s" % (r["label"][:120], key[:120])] = row
    return out


def _claims(d):
    """A row per claim (its id) with what was claimed and what was measured, each where it is a
    number (a claim that is not one has null with a reason in the layout): unit 1, neither better
    nor worse, not timed."""
    out = {}
    for c in d["claims"]:
        row = {STATUS: ("ok", None)}
        for name in ("claimed", "measured"):
            if c[name] is not None:
                row[name] = ("1", "neither", False, c[name], [])
        out[c["id"]] = row
    return out


def _q_sweep(d):
    """A row per Q ("fq:Q=" and Q to 10 significant digits) with its figures; cq2's row (f2)
    and the minimising Q's (best)."""
    out = {}
    for i, q in enumerate(d["Q"]):
        out["fq:Q=%.10g" % q] = {"Q": ("1", "neither", False, q, []),
                                 "max_rel": ("1", "lower", False, d["max_rel"][i], []),
                                 "max_abs": ("1", "lower", False, d["max_abs"][i], []),
                                 "max_abs_attenuation": ("1", "lower", False, d["max_abs_attenuation"][i], []),
                                 "max_rel_at_n": ("1", "neither", False, d["max_rel_at_n"][i], []),
                                 STATUS: ("ok", None)}
    out["cq2 (f2 of paper 2)"] = {"max_rel": ("1", "lower", False, d["f2"]["max_rel"], []),
                                  "max_abs": ("1", "lower", False, d["f2"]["max_abs"], []), STATUS: ("ok", None)}
    b = d["best"]
    out["fq at the best Q"] = {"Q": ("1", "neither", False, b["Q"], []),
                               "max_rel": ("1", "lower", False, b["max_rel"], []),
                               "max_abs": ("1", "lower", False, b["max_abs"], []),
                               "host_max_rel": ("1", "lower", False, b["host_max_rel"], []), STATUS: ("ok", None)}
    return out


def _physical(d):
    """A row per cost row (its model): the rate of the median launch (timed; the rows carry the
    normalised repetitions, not absolute ones), the ratios, the check, the albedo and He's terms
    where the layout has them; then a row per angle of He's terms table ("He terms | THETA deg")
    with the mirror and off-mirror counts per sigma0/lambda."""
    out = {}
    figs = (("ratio_to_fq2", "neither"), ("ratio_to_phong", "neither"), ("ratio_to_pow", "neither"),
            ("check_max_abs_of_peak", "lower"), ("albedo_normal_incidence", "neither"), ("he_terms_mean", "neither"),
            ("he_terms_max", "neither"))
    for r in d["cost"]["rows"]:
        row = {"evaluations_per_s": ("1/s", "higher", True, r["evaluations_per_s"], []), STATUS: ("ok", None)}
        for name, direction in figs:
            if name in r:
                row[name] = ("1", direction, False, r[name], [])
        out[r["model"]] = row
    he = d["he_terms"]
    for i, theta in enumerate(he["theta_deg"]):
        row = {STATUS: ("ok", None)}
        for k, ratio in enumerate(he["sigma0_over_lambda"]):
            row["terms_mirror@%s" % _g(ratio)] = ("1", "neither", False, he["mirror"][i][k], [])
            row["terms_off@%s" % _g(ratio)] = ("1", "neither", False, he["off_mirror"][i][k], [])
        out["He terms | %s deg" % _g(theta)] = row
    return out


def _energy(d):
    """A row per model and integrand of the albedo tables (the largest albedo and where: n, theta_i
    in degrees, neither better higher nor lower; the refinement's change and the normal-incidence
    difference from the closed form, errors), per model of the lobes' reciprocity (the worst
    difference of the peak on the device with its n, the device's evaluation error where written,
    on the host) and per model and shading mode of the image pass's (device, host, pairs lit)."""
    def fig(unit, direction, v):
        return (unit, direction, False, v, [])
    out = {}
    for m in d["albedo"]["models"]:
        out["albedo | %s | %s" % (m["model"], m["integrand"])] = {
            "max_albedo": fig("1", "neither", m["max_albedo"]), "max_at_n": fig("1", "neither", m["max_at_n"]),
            "max_at_theta_i_deg": fig("deg", "neither", m["max_at_theta_i_deg"]),
            "refine_change": fig("1", "lower", m["refine_change"]),
            "normal_incidence_max_diff": fig("1", "lower", m["normal_incidence_max_diff"]), STATUS: ("ok", None)}
    for m in d["reciprocity"]["models"]:
        dev, host = m["device_worst"], m["host_worst"]
        row = {"device.max_diff_of_peak": fig("1", "lower", dev["max_diff_of_peak"]),
               "device.at_n": fig("1", "neither", dev["n"]),
               "host.max_diff_of_peak": fig("1", "lower", host["max_diff_of_peak"]), STATUS: ("ok", None)}
        if "max_eval_error_of_peak" in dev:
            row["device.max_eval_error_of_peak"] = fig("1", "lower", dev["max_eval_error_of_peak"])
        out["reciprocity | %s" % m["model"]] = row
    for m in d["reciprocity_image_pass"]["models"]:
        out["reciprocity_image_pass | %s | mode %d" % (m["model"], m["shading_mode"])] = {
            "device_max_rel_diff": fig("1", "lower", m["device_max_rel_diff"]),
            "host_max_rel_diff": fig("1", "lower", m["host_max_rel_diff"]),
            "pairs_lit_both_ways": fig("1", "neither", m["pairs_lit_both_ways"]), STATUS: ("ok", None)}
    return out


KINDS = {"throughput": _throughput, "accuracy": _accuracy, "render": _render, "fit": _fit, "frontier": _frontier,
         "claims": _claims, "q_sweep": _q_sweep, "physical": _physical, "energy": _energy,
         "measured": _measured}


def expected(doc):
    kind = doc["schema"].split(".")[1].split("/")[0]
    return KINDS[kind](doc)


def as_read(rows_doc):
    """The same mapping of a brdfbench.rows/1 document (what `brdfbench rows --format json` printed)."""
    out = {}
    for r in rows_doc["rows"]:
        out[r["row"]] = {m["name"]: (m["unit"], m["direction"], m["timed"], m["value"], m.get("reps", []))
                         for m in r["metrics"]}
        out[r["row"]][STATUS] = (r["status"], r.get("reason"))
    return out


def same(want, got):
    """The differences between two mappings (empty when they agree; values compared exactly: both
    come from the same 17-digit numbers of the file)."""
    diffs = []
    for k in sorted(set(want) | set(got)):
        if k not in want or k not in got:
            diffs.append("row %r only in %s" % (k, "the program's rows" if k in got else "the expected rows"))
            continue
        for m in sorted(set(want[k]) | set(got[k])):
            a, b = want[k].get(m), got[k].get(m)
            if m == STATUS:
                if a != b:
                    diffs.append("%s: status expected %r, read %r" % (k, a, b))
                continue
            if a != b and not (a and b and a[:3] == b[:3] and a[4] == b[4] and
                               isinstance(a[3], float) and isinstance(b[3], float) and math.isnan(a[3]) and math.isnan(b[3])):
                diffs.append("%s / %s: expected %r, read %r" % (k, m, a, b))
    return diffs


if __name__ == "__main__":
    # rows_layouts.py RESULT_FILE ROWS_JSON: the rows the program read agree with the layout's
    result, rows = (json.load(open(p)) for p in sys.argv[1:3])
    d = same(expected(result), as_read(rows))
    print("\n".join(d[:10]), file=sys.stderr) if d else None
    sys.exit(1 if d else 0)
