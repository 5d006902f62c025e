#!/usr/bin/env python3
"""The phantom worked example of docs/identification.md (issue 14, test 3): for each silicone grade,
the 10 repeats converted by `tmlab data convert`, every STRIDE-th sample of each kept (the fit's
cost scales with the samples; the curves are smooth at 10 Hz), combined into one tmlab-measured/1
data set with a test_id per repeat, fitted by `tmlab fit` with the homogeneous unconfined-compression
surrogate for each law (poisson fixed: nearly incompressible, as the authors' incompressible fits),
ranked by AIC and BIC, and compared with the authors' ranking by AIC in
calibration/data/phantom/upstream_hyperelastic_parameters.json ("engineering" fits).

Usage: phantom_ranking.py TMLAB_BINARY WORK_DIR [STRIDE] [POISSON]
Every tool is started with an argument vector (no shell)."""
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
PHANTOM = os.path.join(ROOT, "calibration", "data", "phantom")
GRADES = ["EF10_0T", "EF30_0T", "EF50_0T"]
REPEATS = ["A1", "A2", "A3", "A4", "A5", "B1", "B2", "B3", "B4", "B5"]
# Our SPEC -> the authors' model key (their one-term forms are the same strain energies).
LAWS = [("stvk", None), ("neo_hookean", "Neo Hookean"), ("mooney_rivlin", "Mooney Rivlin_o1"),
        ("yeoh", "Yeoh_o3"), ("ogden", "Ogden_o1"), ("ogden:2", "Ogden_o2")]


def run(argv):
    p = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return p.returncode, p.stdout


def combine(tmlab, work, grade, stride):
    conv = os.path.join(work, "converted")
    rows, meta = [], None
    for r in REPEATS:
        src = os.path.join(PHANTOM, grade, "%s_%s.csv" % (grade, r))
        code, out = run([tmlab, "data", "convert", src, "--out", conv])
        if code:
            sys.exit(out)
        with open(os.path.join(conv, "%s_%s.csv" % (grade, r))) as f:
            lines = f.read().split("\n")[1:]
        lines = [ln for ln in lines if ln]
        for i, ln in enumerate(lines):
            if i % stride == 0 or i == len(lines) - 1:
                rows.append(ln + "," + r)
        with open(os.path.join(conv, "%s_%s.json" % (grade, r))) as f:
            meta = json.load(f)
    meta["name"] = grade
    meta["notes"] = meta["notes"] + " Combined by phantom_ranking.py: the 10 repeats as tests, every %d-th sample." % stride
    os.makedirs(os.path.join(work, "combined"), exist_ok=True)
    csv = os.path.join(work, "combined", grade + ".csv")
    with open(csv, "w") as f:
        f.write("time_s,displacement_m,force_N,test_id\n" + "\n".join(rows) + "\n")
    with open(os.path.join(work, "combined", grade + ".json"), "w") as f:
        json.dump(meta, f, indent=2)
    return csv, len(rows)


def main():
    tmlab, work = sys.argv[1], sys.argv[2]
    stride = int(sys.argv[3]) if len(sys.argv) > 3 else 10
    poisson = sys.argv[4] if len(sys.argv) > 4 else "0.499"
    with open(os.path.join(PHANTOM, "upstream_hyperelastic_parameters.json")) as f:
        upstream = json.load(f)["engineering"]
    table = {}
    for grade in GRADES:
        csv, n = combine(tmlab, work, grade, stride)
        table[grade] = {"samples": n, "fits": {}}
        for spec, _ in LAWS:
            out = os.path.join(work, "fits", grade + "-" + spec.replace(":", ""))
            code, text = run([tmlab, "fit", csv, "--model", spec + ",poisson=" + poisson, "--out", out, "--quiet"])
            if code:
                table[grade]["fits"][spec] = {"error": text.strip().splitlines()[-1]}
                continue
            with open(os.path.join(out, "fit.json")) as f:
                fj = json.load(f)
            table[grade]["fits"][spec] = {
                "aic": fj["aic"], "bic": fj["bic"], "rms_percent_peak": fj["residual_rms_percent_of_peak"],
                "rms_N": fj["residual_rms_N"], "forward_solves": fj["forward_solves"], "wall_seconds": fj["wall_seconds"],
                "parameters": {p["name"]: [p["value"], p["standard_error"]] for p in fj["parameters"] if not p["fixed"]},
                "confounded": [[c["a"], c["b"], c["correlation"]] for c in fj["confounded"]]}
        ok = {s: v for s, v in table[grade]["fits"].items() if "aic" in v}
        ours = sorted(ok, key=lambda s: ok[s]["aic"])
        theirs = sorted([(s, k) for s, k in LAWS if k in upstream[grade]], key=lambda sk: upstream[grade][sk[1]]["AIC"])
        table[grade]["rank_aic"] = ours
        table[grade]["rank_bic"] = sorted(ok, key=lambda s: ok[s]["bic"])
        table[grade]["upstream_rank_aic"] = [s for s, _ in theirs]
        table[grade]["upstream"] = {s: {"model": k, "parameters_kPa": upstream[grade][k]["parameters"],
                                        "AIC": upstream[grade][k]["AIC"]} for s, k in theirs}
        print("%s (%d samples): ours by AIC: %s" % (grade, n, " < ".join(ours)))
        print("%s  ours by BIC: %s" % (" " * len(grade), " < ".join(table[grade]["rank_bic"])))
        print("%s  upstream by AIC: %s" % (" " * len(grade), " < ".join(table[grade]["upstream_rank_aic"])))
        for s in [x for x, _ in LAWS]:
            v = table[grade]["fits"].get(s, {})
            if "aic" in v:
                ps = ", ".join("%s %.4g +- %.2g" % (k, a, b if b is not None else float("inf")) for k, (a, b) in v["parameters"].items())
                print("   %-14s AIC %10.1f BIC %10.1f RMS %6.2f %% of peak  %s" % (s, v["aic"], v["bic"], v["rms_percent_peak"], ps))
            else:
                print("   %-14s %s" % (s, v.get("error", "")))
    with open(os.path.join(work, "phantom_ranking.json"), "w") as f:
        json.dump(table, f, indent=2)
    print("wrote " + os.path.join(work, "phantom_ranking.json"))


if __name__ == "__main__":
    main()
