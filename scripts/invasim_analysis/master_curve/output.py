"""Writes the fit tables: fits.csv and fits.json (per curve a, b with errors; the fit of a
across curves), points.csv (state points of every curve) and rows.csv (rA_t, A_n and
steadiness per job)."""

import csv
import json
import math
import os

from .. import atomic

CURVE_COLUMNS = ["curve", "state_points", "jobs", "a", "a_error", "b", "b_error", "log10_a",
                 "log10_a_error", "chi2", "dof", "beta", "P", "tau_g", "tau_d", "tau_d_error",
                 "tau_g_over_tau_d", "error_scale", "not_a_fit", "excluded_from_scale_fit",
                 "fit_note"]


def _clean(v):
    """JSON/CSV-friendly value: numpy scalars to float, nan/inf to None."""
    if hasattr(v, "item"):
        v = v.item()
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def _text(v):
    v = _clean(v)
    return "" if v is None else (repr(v) if isinstance(v, float) else str(v))


def curve_record(c):
    rec = {k: _clean(c.get(k)) for k in CURVE_COLUMNS if k not in ("curve", "state_points")}
    rec.update({"curve": c["name"], "group": c["group"], "state_points": len(c["points"]),
                "varying_within_curve": c["varying"], "tau_d_dropped": c["tau_d_dropped"],
                "plateaus": list(c["plateaus"])})
    return rec


def write_tables(out_dir, result, settings):
    """Writes fits.csv, fits.json, points.csv, rows.csv into out_dir (each atomically:
    atomic.py); returns their paths."""
    curves = result["curves"]
    # Group keys as columns of fits.csv, unless fits.csv has them already (beta, P).
    group_keys = [k for k in (curves[0]["group"] if curves else []) if k not in CURVE_COLUMNS]
    paths = {n: os.path.join(out_dir, n) for n in ("fits.csv", "fits.json", "points.csv",
                                                   "rows.csv")}
    with atomic.open_text(paths["fits.csv"]) as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(CURVE_COLUMNS[:1] + group_keys + CURVE_COLUMNS[1:])
        for c in curves:
            rec = curve_record(c)
            w.writerow([rec["curve"]] + [c["group"][k] for k in group_keys]
                       + [_text(rec[k]) for k in CURVE_COLUMNS[1:]])
    scale = {k: _clean(v) for k, v in result["scale_fit"].items()}
    unsteady = [{"job_id": r.get("job_id", ""), "curve": result["curve_of"][i], "why": why}
                for i, (r, why) in enumerate(zip(result["rows"], result["unsteady"])) if why]
    doc = {"settings": settings, "normalisation": result["normalisation"],
           "plateau_fits": [{k: _clean(v) for k, v in p.items()}
                            for p in result["plateau_fits"]],
           "curves": [curve_record(c) for c in curves], "scale_fit": scale,
           "not_steady": unsteady}
    with atomic.open_text(paths["fits.json"]) as f:
        json.dump(doc, f, indent=2, sort_keys=False)
        f.write("\n")
    with atomic.open_text(paths["points.csv"]) as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["curve", "x", "x_error", "A_n", "A_n_error", "replicates", "E_c", "jobs"])
        for c in curves:
            for p in sorted(c["points"], key=lambda p: p["x"]):
                jobs = " ".join(result["rows"][i].get("job_id", "") for i in p["rows"])
                w.writerow([c["name"], _text(p["x"]), _text(p["x_error"]), _text(p["A_n"]),
                            _text(p["A_n_error"]), p["replicates"], _text(p["x"] / c["a"]), jobs])
    with atomic.open_text(paths["rows.csv"]) as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["job_id", "curve", "x", "rA_t", "A_n", "steady", "not_steady_because"])
        for i, r in enumerate(result["rows"]):
            why = result["unsteady"][i]
            w.writerow([r.get("job_id", ""), result["curve_of"][i], _text(result["x"][i]),
                        _text(result["rA_t"][i]), _text(result["A_n"][i]),
                        "false" if why else "true", why or ""])
    return paths
