#include "verification/studies/paper_experiments.hpp"

#include "core/results/series_names.hpp"

#include "core/base/error.hpp"
#include "core/config/config_reader.hpp"

#include <cstdio>

namespace tmlab::tm {

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

/// The parts every run shares: mesh, material with the Prony series and scheme, fixed base.
nlohmann::json base_case(const nlohmann::json& p, const std::string& scheme, const std::string& id) {
  nlohmann::json mat = p.at("material");
  mat["viscoelastic"] = {{"scheme", scheme}, {"prony", p.at("prony")}};
  return {{"name", id},
          {"model", "tensor_mass"},
          {"mesh", {{"file", p.at("mesh")}}},
          {"material", mat},
          {"boundary", nlohmann::json::array({{{"name", "base"}, {"nodes", p.at("base")}}})},
          {"output", {{"every", 1000000}, {"plots", false}, {"vtu", false}}}};
}

}  // namespace

PaperFigure paper_figure(const std::string& name, const nlohmann::json& params, const std::string& where) {
  // Validate the parameter document strictly (the figure-specific block too).
  ConfigReader r(params, where);
  r.require<std::string>("mesh");
  r.raw("base");
  r.raw("material");
  r.raw("prony");
  const auto schemes = r.require<std::vector<std::string>>("schemes");
  if (schemes.empty()) throw r.error("schemes", "must name at least one scheme");
  for (const char* f : {"fig5", "fig6", "fig7"})
    if (r.has(f)) r.raw(f);
  r.finish();
  if (!params.contains(name)) {
    if (name != "fig5" && name != "fig6" && name != "fig7")
      throw Error("unknown paper figure '" + name + "' (expected fig5, fig6 or fig7)");
    throw Error(where + ": no '" + name + "' block");
  }

  PaperFigure fig;
  fig.name = name;
  ConfigReader f(params.at(name), where, name);
  if (name == "fig5") {
    fig.title = "Creep under constant force (Xu et al. 2011, Fig. 5)";
    fig.xlabel = "time [s]";
    fig.ylabel = "displacement of the loaded node [mm]";
    const auto node = f.require<std::vector<double>>("node");
    const double radius = f.positive("patch_radius");
    const auto forces = f.require<std::vector<double>>("forces");
    const double t_end = f.positive("t_end"), dt = f.positive("dt");
    f.finish();
    if (node.size() != 3) throw f.error("node", "must be [x, y, z]");
    for (const auto& s : schemes)
      for (const char* where_load : {"node", "patch"})
        for (double F : forces) {
          PaperRun run;
          run.scheme = s;
          run.id = s + "_" + where_load + "_" + num(F) + "N";
          run.label = s + ", " + where_load + ", " + num(F) + " N";
          run.case_doc = base_case(params, s, run.id);
          const nlohmann::json sel = std::string(where_load) == "node"
                                         ? nlohmann::json{{"sphere", {{"center", node}, {"radius", 1e-6}}}}
                                         : nlohmann::json{{"sphere", {{"center", node}, {"radius", radius}}}};
          // The force is switched on within the first step and then held (creep test).
          run.case_doc["loads"] =
              nlohmann::json::array({{{"type", "nodal_force"},
                                      {"name", "push"},
                                      {"nodes", sel},
                                      {"force", {0.0, 0.0, -F}},
                                      {"function", {{"type", "ramp"}, {"t0", 0.0}, {"t1", dt}}}}});
          run.case_doc["solver"] = {
              {"type", "static"}, {"t_end", t_end}, {"steps", static_cast<int>(t_end / dt + 0.5)}};
          run.case_doc["output"]["probes"] = nlohmann::json::array({{{"name", "node"}, {"point", node}}});
          run.x = "time";
          run.y = series_names::component(series_names::probe("node"), "z");
          run.y_sign = -1e3;
          fig.runs.push_back(run);
        }
  } else if (name == "fig6") {
    fig.title = "Stress relaxation after a 1 cm indentation in 1 s (Xu et al. 2011, Fig. 6)";
    fig.xlabel = "time [s]";
    fig.ylabel = "indentation force [N]";
    const auto nodes = f.require<std::vector<std::vector<double>>>("nodes");
    const double depth = f.positive("depth"), ramp = f.positive("ramp"), hold = f.positive("hold"),
                 dt = f.positive("dt");
    f.finish();
    for (const auto& s : schemes)
      for (std::size_t k = 0; k < nodes.size(); ++k) {
        if (nodes[k].size() != 3) throw f.error("nodes", "entry " + std::to_string(k) + " must be [x, y, z]");
        PaperRun run;
        run.scheme = s;
        run.id = s + "_node" + std::to_string(k + 1);
        run.label = s + ", node " + std::to_string(k + 1);
        run.case_doc = base_case(params, s, run.id);
        run.case_doc["boundary"].push_back({{"name", "push"},
                                            {"nodes", {{"sphere", {{"center", nodes[k]}, {"radius", 1e-6}}}}},
                                            {"components", "z"},
                                            {"value", {0.0, 0.0, -depth}},
                                            {"function", {{"type", "ramp"}, {"t0", 0.0}, {"t1", ramp}}}});
        const double t_end = ramp + hold;
        run.case_doc["solver"] = {
            {"type", "static"}, {"t_end", t_end}, {"steps", static_cast<int>(t_end / dt + 0.5)}};
        run.x = "time";
        run.y = series_names::component(series_names::reaction("push"), "z");
        run.y_sign = -1.0;
        fig.runs.push_back(run);
      }
  } else {
    fig.title = "Hysteresis of a load-unload cycle (Xu et al. 2011, Fig. 7)";
    fig.xlabel = "indentation [mm]";
    fig.ylabel = "indentation force [N]";
    const auto node = f.require<std::vector<double>>("node");
    const double depth = f.positive("depth");
    const auto periods = f.require<std::vector<double>>("periods");
    const int steps = f.get<int>("steps_per_cycle", 200);
    f.finish();
    if (steps < 4) throw f.error("steps_per_cycle", "must be >= 4");
    for (const auto& s : schemes)
      for (double P : periods) {
        if (!(P > 0.0)) throw f.error("periods", "must be > 0");
        PaperRun run;
        run.scheme = s;
        run.id = s + "_period" + num(P) + "s";
        run.label = s + ", cycle " + num(P) + " s";
        run.case_doc = base_case(params, s, run.id);
        run.case_doc["boundary"].push_back(
            {{"name", "push"},
             {"nodes", {{"sphere", {{"center", node}, {"radius", 1e-6}}}}},
             {"components", "z"},
             {"value", {0.0, 0.0, -depth}},
             {"function", {{"type", "table"}, {"points", {{0.0, 0.0}, {P / 2, 1.0}, {P, 0.0}}}}}});
        run.case_doc["solver"] = {{"type", "static"}, {"t_end", P}, {"steps", steps}};
        run.case_doc["output"]["probes"] = nlohmann::json::array({{{"name", "node"}, {"point", node}}});
        run.x = series_names::component(series_names::probe("node"), "z");
        run.x_sign = -1e3;
        run.y = series_names::component(series_names::reaction("push"), "z");
        run.y_sign = -1.0;
        fig.runs.push_back(run);
      }
  }
  return fig;
}

}  // namespace tmlab::tm
