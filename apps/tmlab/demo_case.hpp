// The demo case, embedded so that `tmlab demo` runs on defaults that ship with the binary.
// It is the same case as cases/liver-probe.json (test_cli checks that the two agree).
#pragma once

namespace tmlab::cli {

inline constexpr const char* kDemoCase = R"JSON({
  "name": "liver-probe",
  "description": "liver pressed 15 mm by a probe, static, 10 load steps (the demo)",
  "model": "tensor_mass",
  "mesh": {"file": "meshes/liver.msh"},
  "material": {"law": "stvk", "E": 5000, "nu": 0.45, "density": 1060},
  "boundary": [
    {"name": "base", "nodes": {"box": {"min": [-1, -1, 0], "max": [1, 1, 1.4983]}}},
    {"name": "probe", "nodes": {"sphere": {"center": [-0.05083364, -0.05144245, 1.60851524], "radius": 0.02}},
     "components": "xyz", "value": [0, 0, -0.015], "function": {"type": "ramp", "t0": 0, "t1": 1}}
  ],
  "solver": {"type": "static", "steps": 10, "t_end": 1.0},
  "output": {"probes": [{"name": "probe_tip", "point": [-0.05083364, -0.05144245, 1.60851524]},
                        {"name": "right_lobe", "point": [0.05, -0.05, 1.58]}]}
}
)JSON";

}  // namespace tmlab::cli
