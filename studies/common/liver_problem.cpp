#include "studies/common/liver_problem.hpp"

#include "core/base/error.hpp"
#include "core/config/case_config.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <filesystem>

namespace tmlab::tm {

LiverProblem liver_problem(const nlohmann::json& params, const std::string& where,
                           const std::string& tmlab_root) {
  namespace fs = std::filesystem;
  LiverProblem p;
  const fs::path file(params.at("mesh").get<std::string>());
  const fs::path resolved = file.is_absolute() ? file : (fs::path(tmlab_root) / file).lexically_normal();
  if (!fs::exists(resolved)) throw Error(where + ": key 'mesh': file not found: " + resolved.string());
  p.mesh_file = resolved.string();
  // load_case_mesh: the checks of a case's mesh (no inverted or degenerate tet), no scaling or repair.
  MeshReport report;
  int repaired = 0;
  p.mesh = load_case_mesh(MeshSpec{p.mesh_file}, report, repaired);
  const nlohmann::json& m = params.at("material");
  p.young = m.at("E").get<double>();
  p.poisson = m.at("nu").get<double>();
  p.material = StVenantKirchhoff::from_young_poisson(p.young, p.poisson);
  p.density = m.at("density").get<double>();
  p.prony = PronySeries::from_json(params.at("prony"), where, "prony");
  p.base.name = "base";
  p.base.nodes = select_nodes(p.mesh, NodeSelector::from_json(params.at("base"), where + ": base"));
  if (p.base.nodes.empty()) throw Error(where + ": key 'base' selects no nodes");
  return p;
}

}  // namespace tmlab::tm
