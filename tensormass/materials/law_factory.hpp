// Builds a hyperelastic Law from its name and a parameter object (the case file's `material`
// section, as nlohmann::json), with errors naming the offending key.
//
// Names and keys, from the law catalogue (core/constitutive/law_catalogue.hpp; SI units, Pa unless
// noted; docs/theory/hyperelastic-laws.md):
//   stvk, neo_hookean   {"young", "poisson"}  or  {"lambda", "mu"}
//   mooney_rivlin       {"c10", "c01", "kappa"}
//   yeoh                {"c10", "kappa"} and optional "c20", "c30" (default 0)
//   ogden               {"mu": [mu_1, ..., mu_N], "alpha": [alpha_1, ..., alpha_N], "kappa"}
//   veronda_westmann    {"c1", "c2" (dimensionless), "kappa"}
// Keys in `ignored` (e.g. "law", or keys other parts of the case file read) are skipped; any other
// unknown key is an error (a misspelt key must not silently fall back to a default).
#pragma once

#include "core/constitutive/material_law.hpp"
#include "tensormass/materials/law.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

namespace tmlab::tm {

/// The accepted law names, in the catalogue's order (law_name_list()).
std::vector<std::string> law_names();

/// Builds the law `name` from `params` (a JSON object). `where` prefixes every message and names
/// the object in the user's file (e.g. "case.json: material"), keys are reported as
/// "<where>.<key>". Throws tmlab::Error for an unknown name, a non-object, a missing, non-numeric,
/// non-finite or unknown key, and for parameters the law's constructor refuses (the message then
/// names the key(s) and carries the constructor's reason).
Law make_law(const std::string& name, const nlohmann::json& params, const std::string& where,
             const std::vector<std::string>& ignored = {"law"});

/// Builds the law of a case file's material section in plain form (core/constitutive/
/// material_law.hpp: the vocabulary core/config parses into, which knows nothing of tm::Law), through
/// make_law above: the laws given by E and nu from young/poisson, the others from their coefficients
/// and kappa (each law's parameters as its catalogue row lists them). The same names and the same
/// constructors' checks, so a case file and a parameter object give the same law. `where` prefixes errors
/// (e.g. "case.json: material").
Law make_law(MaterialLaw law, const LawParameters& parameters, const std::string& where);

}  // namespace tmlab::tm
