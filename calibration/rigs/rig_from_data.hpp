// A measured data set's test as a rig (issue 14, docs/rigs.md "From measured data"): the data's
// JSON names the test type, the indenter, the sample and its supports; the test's (time_s,
// displacement_m) columns are the driving history. Nothing is entered by hand.
//
// Mapping (measured-data key -> RigSpec field):
//   test                         -> test
//   indenter.shape, .radius_m    -> indenter (sphere, flat_punch; a cylinder on its side has no rig)
//   sample.shape block, size_m   -> Block, size_x, size_y, height (= size_m[2], the loaded axis)
//   sample.shape cylinder        -> Cylinder, radius, height (platen tests only: indentation rigs
//                                   are blocks)
//   sample.shape half_space      -> (indentation only) a block on a frictionless support, height
//                                   20 a_max and side twice that (at least 10 R), a_max = sqrt(R d_max)
//                                   the largest Hertz contact radius (a flat punch: a = R). A finite
//                                   layer is stiffer than the half-space: by about 0.39 a/h = 2 % at
//                                   the deepest sample (Dimitriadis et al. 2002, frictionless layer)
//   sample.bottom                -> bottom (indentation)
//   sample.platens               -> platens (compression, tension)
//   time_s - time_s[0], displacement_m -> history; when the first sample is already loaded
//                                   (displacement != 0), the unloaded state is put one sampling
//                                   interval before it (the history must start at rest).
#pragma once

#include "calibration/data/measured_data.hpp"
#include "calibration/rigs/rig.hpp"

#include <cstddef>

namespace tmlab::rigs {

/// The mesh resolution of rigs made from data (the data say nothing about it).
struct RigFromDataMesh {
  int cells = 12;        ///< cells across the smaller lateral size (cylinder: 2 per ring)
  int layers = 6;        ///< cells through the height
  double grading = 2.0;  ///< indentation: power of the grading towards the indenter
  /// > 0: the contact rule instead (RigSpec::contact_cells across a_max; platen tests: the default
  /// rim_cells), and cells, layers, grading are not used. 0 (the default) keeps the explicit form.
  int contact_cells = 0;
};

/// The rig of test `k` of `data`; tmlab::Error naming the data set's JSON key (or the test and
/// sample) when something the rig needs is missing or has no rig (a cylinder indenter, an indented
/// cylinder, platens missing from a compression test, a history that leaves the sample ...).
RigSpec rig_from_data(const measured::DataSet& data, std::size_t k, const RigFromDataMesh& mesh = {});

/// The time shift the history of test `k` got: 0, or one sampling interval when the first sample is
/// already loaded (data time t is rig time t - time_s[0] + shift).
double rig_from_data_time_shift(const measured::DataSet& data, std::size_t k);

}  // namespace tmlab::rigs
