// Tests of the closed-form forward models of the fit: they return the closed forms, and data they
// cannot fit are refused with a clear error (issue 14, test 4: bad data rejected).
#include "calibration/fit/surrogates.hpp"

#include "calibration/closed_forms/homogeneous.hpp"
#include "calibration/closed_forms/indentation.hpp"
#include "calibration/fit/synthetic_data.hpp"
#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::fit {
namespace {

using synthetic::compression_data;
using synthetic::indentation_data;

std::vector<double> values(const Problem& p) {
  std::vector<double> x;
  for (const auto& q : p.parameters) x.push_back(q.value);
  return x;
}

TEST(Surrogates, IndentationIsHertzOrLeeRadok) {
  measured::DataSet d = indentation_data({0.5e-3, 1e-3});
  synthetic::set_forces(d, std::vector<double>(2 * d.tests[0].size(), 1e-3));
  Problem hertz = make_surrogate_problem(d, parse_model_spec("stvk"), {{"young", 4000.0}, {"poisson", 0.4}});
  const std::vector<double> f = hertz.model->predict(values(hertz));
  EXPECT_EQ(hertz.model->name(), "hertz_sphere");
  const std::size_t last = d.tests[0].size() - 1;
  EXPECT_NEAR(f[last], closed_forms::hertz_force(4000.0, 0.4, 5e-3, 0.5e-3), 1e-15);
  Problem lr =
      make_surrogate_problem(d, parse_model_spec("stvk+prony:1,young=3000,e1=1000,tau1=2,poisson=0.4"));
  EXPECT_EQ(lr.model->name(), "lee_radok_sphere");
  const std::vector<double> g = lr.model->predict(values(lr));
  closed_forms::RelaxationModulus e{3000.0, {1000.0}, {2.0}};
  closed_forms::DepthHistory h{d.tests[1].time_s, d.tests[1].displacement_m};
  const std::vector<double> ref = closed_forms::lee_radok_sphere(e, 0.4, 5e-3, h);
  EXPECT_NEAR(g.back(), ref.back(), 1e-12 * ref.back());
}

TEST(Surrogates, CompressionIsTheHomogeneousPlatenState) {
  measured::DataSet d = compression_data(0.3, 31);
  synthetic::set_forces(d, std::vector<double>(31, 1.0));
  Problem p = make_surrogate_problem(d, parse_model_spec("neo_hookean"), {{"young", 5e4}, {"poisson", 0.49}});
  const std::vector<double> f = p.model->predict(values(p));
  const tm::Law law = build_law(parse_model_spec("neo_hookean"), values(p));
  const double area = 3.14159265358979323846 * 0.025 * 0.025;
  EXPECT_EQ(f.back(),
            closed_forms::platen_state(law, closed_forms::PlatenTest::Unconfined, 0.03, area, 0.009).force);
}

/// Expects make_surrogate_problem to throw an Error whose message contains `what`.
void expect_refused(const measured::DataSet& d, const std::string& spec, const std::string& what,
                    const std::vector<std::pair<std::string, double>>& weights = {}) {
  try {
    make_surrogate_problem(d, parse_model_spec(spec), {}, weights);
    ADD_FAILURE() << "accepted: " << what;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(Surrogates, BadDataIsRejectedWithAClearError) {
  measured::DataSet zero = indentation_data({1e-3});
  expect_refused(zero, "stvk", "the force is zero at every sample");

  measured::DataSet unload = indentation_data({1e-3});
  synthetic::set_forces(unload, std::vector<double>(unload.tests[0].size(), 1e-3));
  unload.tests[0].displacement_m.back() = 0.5e-3;
  expect_refused(unload, "stvk+prony:1", "the depth decreases while in contact");

  measured::DataSet cyl = unload;
  cyl.meta.indenter->shape = measured::IndenterShape::cylinder;
  expect_refused(cyl, "stvk", "cylinder indenter");
  expect_refused(unload, "yeoh", "small-strain");

  measured::DataSet deep = indentation_data({4e-3}, 20.0, 2e-3);  // contact radius 4.5 mm > 2 mm layer
  synthetic::set_forces(deep, std::vector<double>(deep.tests[0].size(), 1e-3));
  expect_refused(deep, "stvk", "exceeds the layer thickness");

  measured::DataSet neg = indentation_data({1e-3});
  synthetic::set_forces(neg, std::vector<double>(neg.tests[0].size(), -1e-3));
  expect_refused(neg, "stvk", "sign convention");

  measured::DataSet c = compression_data(0.3, 31);
  synthetic::set_forces(c, std::vector<double>(31, 1.0));
  expect_refused(c, "neo_hookean+prony:1", "Prony terms");
  expect_refused(c, "neo_hookean", "--weight names test 'x'", {{"x", 2.0}});
  c.tests[0].displacement_m.back() = 0.031;
  expect_refused(c, "neo_hookean", "reaches the sample height");

  measured::DataSet few = compression_data(0.3, 2);
  synthetic::set_forces(few, {0.0, 1.0});
  expect_refused(few, "mooney_rivlin", "more samples than parameters");

  measured::DataSet hs = compression_data(0.3, 31);
  synthetic::set_forces(hs, std::vector<double>(31, 1.0));
  hs.meta.sample.shape = measured::SampleShape::half_space;
  expect_refused(hs, "neo_hookean", "not a half-space");

  EXPECT_THROW(make_surrogate_problem(c, parse_model_spec("neo_hookean,poisson=0.7")), Error);
  EXPECT_THROW(make_surrogate_problem(c, parse_model_spec("neo_hookean,shear=1")), Error);
}

}  // namespace
}  // namespace tmlab::fit
