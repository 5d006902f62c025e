#!/bin/sh
# Measures the reference solver's assembly, linear-solve and Newton times per load step
# (docs/performance.md). Usage: reference_fem/dealii/bench/measure_performance.sh BUILD_DIR [OUT_DIR]
# Runs each case serially and with `mpirun -np 2`, then prints one table row per run from the
# per-step statistics in summary.json (solver.steps[*]).
set -eu
build=${1:?build directory}
out=${2:-/tmp/tmlab-ref-perf}
root=$(cd "$(dirname "$0")/../../.." && pwd)
ref="$build/apps/tmlab_reference/tmlab_reference"
mkdir -p "$root/build/perf" "$out"
[ -f "$root/build/perf/cube32.msh" ] || "$build/apps/meshtool/meshtool" box "$root/build/perf/cube32.msh" 32 32 32 --hi 0.1 0.1 0.1
run() {  # name np args...
  name=$1; np=$2; shift 2
  if [ "$np" = 1 ]; then "$ref" "$@" --quiet --results "$out/$name"
  else mpirun --allow-run-as-root --oversubscribe -np "$np" "$ref" "$@" --quiet --results "$out/$name"; fi
  echo "$name $np $*" >> "$out/runs.txt"
}
touch "$out/runs.txt"
L="$root/reference_fem/dealii/bench/perf-liver-probe-10mm.json"
C="$root/reference_fem/dealii/bench/perf-cube-200k.json"
for np in ${NPS:-1 2}; do
  run liver-p1-direct-np$np $np "$L"
  run liver-p2-direct-np$np $np "$L" --degree 2
  run liver-p2-amg-np$np $np "$L" --degree 2 --solver cg_amg
  run cube200k-p1-amg-np$np $np "$C" --solver cg_amg
  # The direct solver on the 200k cube is left out: MUMPS runs on Debian's reference BLAS here
  # and one factorisation of the 107,811-DoF system takes minutes (docs/performance.md).
done
/usr/bin/python3 - "$out" <<'PY'
import json, pathlib, sys
out = pathlib.Path(sys.argv[1])
print("| run | DoFs | ranks | steps | Newton its/step | assembly s/step | solve s/step | Newton s/step | linear its/step |")
print("|---|---|---|---|---|---|---|---|---|")
for line in (out / "runs.txt").read_text().splitlines():
    name = line.split()[0]
    s = json.loads(next((out / name).glob("*/summary.json")).read_text())
    st = s["solver"]["steps"]; n = len(st)
    avg = lambda k: sum(x[k] for x in st) / n
    print(f"| {name} | {s['discretisation']['n_dofs']} | {s['discretisation']['mpi_ranks']} | {n} | {avg('newton_iterations'):.1f} | "
          f"{avg('assembly_seconds'):.3f} | {avg('solve_seconds'):.3f} | {avg('newton_seconds'):.3f} | {avg('linear_iterations'):.0f} |")
PY
