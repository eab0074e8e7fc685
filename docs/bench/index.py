#!/usr/bin/env python3
"""Writes docs/bench/README.md from the bench's CSV files (run after `fathom bench ... --out docs/bench`).

    python3 docs/bench/index.py
"""
import csv, glob, os, re

HERE = os.path.dirname(os.path.abspath(__file__))
PRESETS = ["draft", "interactive", "final", "reference"]
MAX_REFERENCE_FLIPS = 1.0  # % of pixels: a reference that flips more against a stricter render is not converged
MAX_REFERENCE_RMSE = 0.1  # nor one whose colour is further than this from it (deep_zoom's 0.126)


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    runs = sorted(os.path.basename(p)[: -len("-knobs.csv")] for p in glob.glob(os.path.join(HERE, "*-knobs.csv")))
    out = ["# What accuracy costs", "",
           "Made by `fathom bench` on this repository's scenes: every accuracy knob swept on its own, the presets,",
           "and every effect compiled out / in / in but switched off, each measured for time (median of 3 images",
           "after a warm-up, wall clock around glFinish) and for error against a reference render of the same two",
           "views (colour RMSE and PSNR of the 8-bit image, depth error in pixel footprints, hit/miss flips, the",
           "IoU of the hit masks and how far the farthest flipped pixel lies from the reference's silhouette, steps).",
           "The reference is the `reference` preset at 64 spp with every hit located at float resolution",
           "(`quality.refine=64`): it does not share the near-miss bias of the hit threshold it judges. Fractals",
           "are the exception by definition: the footprint rule defines their surface at a level of detail.",
           "Each run's summary says how its reference was checked for convergence. Runs made since the bench",
           "learned them also have an HTML report (one self-contained page: the overview of the presets and the",
           "Pareto front, one small plot a knob, the tables, the machine), times with their 95 % intervals and a",
           "Pareto front built from them. Every shipped scene has a run. Remade (2026-11-27, llvmpipe, 2 cores) with",
           "`for s in csg himalaya jacksboro mandelbox mandelbulb menger noise; do build/fathom bench --scene $s --size 240x135 --runs 3 --out docs/bench; done`,",
           "`build/fathom bench --scene jacksboro --name jacksboro-linear --set terrain.method=linear --size 240x135 --runs 3 --out docs/bench`,",
           "and `build/fathom bench --scene S --quick --out docs/bench` (160x90, three values a knob) for spray, dem and the",
           "formula scenes; then `python3 docs/bench/index.py`. A fractal's reference often flips more than 1 % of its",
           "pixels against a stricter one: a stricter threshold *is* a finer level of detail there, a different surface;",
           "a reference more than 0.1 RMSE from the stricter one (the deep zoom's, at the edge of float precision) is",
           "not converged either, and both are left out of the guarantees.", ""]
    worst = {p: {"rmse": 0.0, "depth": 0.0, "depth_max": 0.0, "flips": 0.0, "iou": 1.0, "edge": 0.0} for p in PRESETS}
    unconverged = []
    for name in runs:
        r = rows(os.path.join(HERE, name + "-knobs.csv"))
        summary = open(os.path.join(HERE, name + "-summary.md")).read()
        m = re.search(r"differs from it by RMSE ([0-9.]+) .*?, ([0-9.]+) % flipped", summary)
        conv_rmse, conv_flips = float(m.group(1)), float(m.group(2))
        converged = conv_flips <= MAX_REFERENCE_FLIPS and conv_rmse <= MAX_REFERENCE_RMSE
        if not converged:
            unconverged.append(name)
        size = "%sx%s" % (r[0]["width"], r[0]["height"])
        report = os.path.exists(os.path.join(HERE, name + "-report.html"))
        out += ["## %s" % name, "",
                ("[report (HTML)](%s-report.html) · [overview](%s-overview.png) · " % (name, name) if report else "") +
                "[summary, every knob](%s-summary.md) · [plot](%s-plot.png) · [CSV](%s-knobs.csv) · "
                "[effects](%s-effects.csv), %s. Reference against a stricter render: RMSE %.4f, %.2f %% flipped "
                "pixels%s." % (name, name, name, name, size, conv_rmse, conv_flips,
                               "" if converged else " (**not converged**: left out of the guarantees below)"), "",
                "| preset | ms per image | RMSE | PSNR dB | depth mean / max (pixel footprints) | flips % | IoU | edge px | steps/px | out of steps % |",
                "|---|---|---|---|---|---|---|---|---|---|"]
        for row in r:
            if row["knob"] != "preset":
                continue
            p = row["value"]
            out.append("| %s | %.1f | %.4f | %.1f | %.3f / %.2f | %.2f | %.4f | %.1f | %.1f | %.2f |" % (
                p, float(row["ms_per_image"]), float(row["rmse"]), float(row["psnr_db"]), float(row["depth_mean_fp"]),
                float(row["depth_max_fp"]), 100 * float(row["flip_share"]), float(row["iou"]),
                float(row["edge_max_px"]), float(row["mean_steps"]), 100 * float(row["out_of_steps_share"])))
            if p != "reference" and converged:
                w = worst[p]
                w["rmse"] = max(w["rmse"], float(row["rmse"]))
                w["depth"] = max(w["depth"], float(row["depth_mean_fp"]))
                w["depth_max"] = max(w["depth_max"], float(row["depth_max_fp"]))
                w["flips"] = max(w["flips"], 100 * float(row["flip_share"]))
                w["iou"] = min(w["iou"], float(row["iou"]))
                w["edge"] = max(w["edge"], float(row["edge_max_px"]))
        fx = rows(os.path.join(HERE, name + "-effects.csv"))
        used = [e for e in fx if e["in_scene"] == "1"]
        if used:
            out += ["", "Effects this scene uses, ms per 1-spp frame: " + "; ".join(
                "%s %.1f out / %.1f in / %.1f in but off" % (e["effect"], float(e["ms_compiled_out"]),
                                                            float(e["ms_compiled_in"]),
                                                            float(e["ms_compiled_in_switched_off"])) for e in used) + "."]
        out += [""]
    out += ["## What each preset guarantees (worst case over the runs whose reference converged)", "",
            "Left out: %s (their reference flipped more than %.0f %% of pixels against a stricter render, or its"
            " colour differed by more than %g RMSE; see each summary)." % (", ".join(unconverged) or "none",
                                                                          MAX_REFERENCE_FLIPS, MAX_REFERENCE_RMSE), "",
            "| preset | colour RMSE ≤ | mean depth error ≤ (pixel footprints) | max depth error (any pixel) | flipped pixels ≤ | silhouette IoU ≥ | silhouette edge moves ≤ (pixels) |",
            "|---|---|---|---|---|---|---|"]
    for p in PRESETS[:-1]:
        w = worst[p]
        out.append("| %s | %.3f | %.2f | %.1f | %.1f %% | %.4f | %.1f |" % (p, w["rmse"], w["depth"], w["depth_max"],
                                                                    w["flips"], w["iou"], w["edge"]))
    out += ["", "IoU is over the worst of the two views; edge moves: the farthest flipped pixel from the reference's",
            "silhouette (a flip inside an object, where a thin gap or hole closes or opens, counts too). Max depth",
            "errors come from a handful of grazing pixels; the mean is the figure that describes the image.", ""]
    with open(os.path.join(HERE, "README.md"), "w") as f:
        f.write("\n".join(out))
    print("wrote docs/bench/README.md for", ", ".join(runs))


if __name__ == "__main__":
    main()
