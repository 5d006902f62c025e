#include "studies/paper/paper_experiments.hpp"

#include "core/results/series_names.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/config_reader.hpp"
#include "core/constitutive/prony.hpp"

namespace tmlab::tm {

namespace {

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

/// A run of scheme `scheme` on the shared case (its loading and series still to set).
PaperRun paper_run(const nlohmann::json& p, const std::string& scheme, const std::string& id,
                   const std::string& label) {
  PaperRun run;
  run.scheme = scheme;
  run.id = id;
  run.label = label;
  run.case_doc = base_case(p, scheme, id);
  return run;
}

/// The nodes within `radius` of `center` (1 um: the one node there).
nlohmann::json sphere(const std::vector<double>& center, double radius = 1e-6) {
  return {{"sphere", {{"center", center}, {"radius", radius}}}};
}

/// The indentation: the node at `node` pushed `depth` down (z) along `function`.
nlohmann::json push_condition(const std::vector<double>& node, double depth, const nlohmann::json& function) {
  return {{"name", "push"},
          {"nodes", sphere(node)},
          {"components", "z"},
          {"value", {0.0, 0.0, -depth}},
          {"function", function}};
}

void set_axes(PaperFigure& fig, std::string title, std::string xlabel, std::string ylabel) {
  fig.title = std::move(title);
  fig.xlabel = std::move(xlabel);
  fig.ylabel = std::move(ylabel);
}

/// The quasi-static solver block: `steps` steps to t_end.
nlohmann::json static_solver(double t_end, int steps) {
  return {{"type", "static"}, {"t_end", t_end}, {"steps", steps}};
}

}  // namespace

PaperFigure paper_figure(const std::string& name, const nlohmann::json& params, const std::string& where) {
  // Validate the parameter document strictly (the figure-specific block too).
  ConfigReader r(params, where);
  r.require<std::string>("mesh");
  r.raw("base");
  r.raw("material");
  r.raw("prony");
  auto schemes = r.require<std::vector<std::string>>("schemes");
  if (schemes.empty()) throw r.error("schemes", "must name at least one scheme");
  // Runs are named and written under the current names (xu2011 for the former seed).
  for (std::string& s : schemes)
    if (const auto named = prony_scheme_from_string(s)) s = to_string(*named);
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
    set_axes(fig, "Creep under constant force (Xu et al. 2011, Fig. 5)", "time [s]",
             "displacement of the loaded node [mm]");
    const auto node = f.require<std::vector<double>>("node");
    const double radius = f.positive("patch_radius");
    const auto forces = f.require<std::vector<double>>("forces");
    const double t_end = f.positive("t_end"), dt = f.positive("dt");
    f.finish();
    if (node.size() != 3) throw f.error("node", "must be [x, y, z]");
    for (const auto& s : schemes)
      for (const char* where_load : {"node", "patch"})
        for (double F : forces) {
          PaperRun run = paper_run(params, s, s + "_" + where_load + "_" + significant(F, 6) + "N",
                                   s + ", " + where_load + ", " + significant(F, 6) + " N");
          const nlohmann::json sel = std::string(where_load) == "node" ? sphere(node) : sphere(node, radius);
          // The force is switched on within the first step and then held (creep test).
          run.case_doc["loads"] =
              nlohmann::json::array({{{"type", "nodal_force"},
                                      {"name", "push"},
                                      {"nodes", sel},
                                      {"force", {0.0, 0.0, -F}},
                                      {"function", {{"type", "ramp"}, {"t0", 0.0}, {"t1", dt}}}}});
          run.case_doc["solver"] = static_solver(t_end, static_cast<int>(t_end / dt + 0.5));
          run.case_doc["output"]["probes"] = nlohmann::json::array({{{"name", "node"}, {"point", node}}});
          run.x = "time";
          run.y = series_names::component(series_names::probe("node"), "z");
          run.y_sign = -1e3;
          fig.runs.push_back(run);
        }
  } else if (name == "fig6") {
    set_axes(fig, "Stress relaxation after a 1 cm indentation in 1 s (Xu et al. 2011, Fig. 6)", "time [s]",
             "indentation force [N]");
    const auto nodes = f.require<std::vector<std::vector<double>>>("nodes");
    const double depth = f.positive("depth"), ramp = f.positive("ramp"), hold = f.positive("hold"),
                 dt = f.positive("dt");
    f.finish();
    for (const auto& s : schemes)
      for (std::size_t k = 0; k < nodes.size(); ++k) {
        if (nodes[k].size() != 3) throw f.error("nodes", "entry " + std::to_string(k) + " must be [x, y, z]");
        PaperRun run =
            paper_run(params, s, s + "_node" + std::to_string(k + 1), s + ", node " + std::to_string(k + 1));
        run.case_doc["boundary"].push_back(
            push_condition(nodes[k], depth, {{"type", "ramp"}, {"t0", 0.0}, {"t1", ramp}}));
        const double t_end = ramp + hold;
        run.case_doc["solver"] = static_solver(t_end, static_cast<int>(t_end / dt + 0.5));
        run.x = "time";
        run.y = series_names::component(series_names::reaction("push"), "z");
        run.y_sign = -1.0;
        fig.runs.push_back(run);
      }
  } else {
    set_axes(fig, "Hysteresis of a load-unload cycle (Xu et al. 2011, Fig. 7)", "indentation [mm]",
             "indentation force [N]");
    const auto node = f.require<std::vector<double>>("node");
    const double depth = f.positive("depth");
    const auto periods = f.require<std::vector<double>>("periods");
    const int steps = f.get<int>("steps_per_cycle", 200);
    f.finish();
    if (steps < 4) throw f.error("steps_per_cycle", "must be >= 4");
    for (const auto& s : schemes)
      for (double P : periods) {
        if (!(P > 0.0)) throw f.error("periods", "must be > 0");
        PaperRun run = paper_run(params, s, s + "_period" + significant(P, 6) + "s",
                                 s + ", cycle " + significant(P, 6) + " s");
        run.case_doc["boundary"].push_back(push_condition(
            node, depth, {{"type", "table"}, {"points", {{0.0, 0.0}, {P / 2, 1.0}, {P, 0.0}}}}));
        run.case_doc["solver"] = static_solver(P, steps);
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
