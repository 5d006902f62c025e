// Quadrature rules on simplices for the analytic checks: the collapsed (Duffy) Gauss-Legendre rule
// on the reference tet (the MMS check's loads and error norms) and Dunavant's 7-point degree-5 rule
// on a triangle (the Hertz check's consistent pressure loads).
#pragma once

#include <array>
#include <vector>

namespace tmlab::verify::numerics {

/// Collapsed Gauss-Legendre rule on the reference tet: barycentric points and weights (sum 1).
struct TetRule {
  std::vector<std::array<double, 4>> bary;
  std::vector<double> weight;
};

/// The q^3-point collapsed rule (q Gauss-Legendre points per direction, by the Golub-Welsch
/// eigenvalue method): exact for polynomials of degree 2q - 3 on the tet (weights sum to 1, the
/// integral relative to the tet's volume).
TetRule duffy_rule(int q);

/// The 7-point degree-5 rule on a triangle (Dunavant): weights (sum 1, relative to the area) and
/// barycentric points.
inline constexpr double kTriW[7] = {0.225,
                                    0.1323941527885062,
                                    0.1323941527885062,
                                    0.1323941527885062,
                                    0.1259391805448271,
                                    0.1259391805448271,
                                    0.1259391805448271};
inline constexpr double kTriB[7][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3},
                                       {0.0597158717897698, 0.4701420641051151, 0.4701420641051151},
                                       {0.4701420641051151, 0.0597158717897698, 0.4701420641051151},
                                       {0.4701420641051151, 0.4701420641051151, 0.0597158717897698},
                                       {0.7974269853530873, 0.1012865073234563, 0.1012865073234563},
                                       {0.1012865073234563, 0.7974269853530873, 0.1012865073234563},
                                       {0.1012865073234563, 0.1012865073234563, 0.7974269853530873}};

}  // namespace tmlab::verify::numerics
