// Linking measures of polylines: the Gauss linking integral (paper eq. 1), the exact linking number
// of two closed curves, and virtual linking (eq. 2), with analytic gradients for task Jacobians.
//
// Sign convention: Lk(A, B) = 1/(4π) ∮∮ (a − b)·(da × db) / |a − b|³ (eq. 1), which is +1 for
// the right-hand rule: B pierces the disc of A along the normal that A's direction gives by the
// right hand. Lk is symmetric: Lk(A, B) = Lk(B, A).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace claspplan::servo {

using Points = std::vector<Eigen::Vector3d>;

/// Thrown when two curves touch or cross (the linking integral is undefined there). Inside a run
/// this is an internal failure (exit 3); callers whose curves are the user's own (`claspplan
/// linking`) turn it into an InputError. Planner code that moves curves may catch it specifically.
class CurvesIntersect : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Checks a polyline: at least 2 points (3 when closed), finite coordinates and no zero-length
/// segment (the closing segment included). Throws std::invalid_argument naming `what`.
void validate_curve(const Points& points, bool closed, const std::string& what);

/// Gauss linking integral of two polylines (eq. 1), summed in closed form over segment pairs
/// (Van Oosterom–Strackee solid angle of each pair's difference quadrilateral). `closed` adds the
/// segment from the last point back to the first. For two closed curves the result is the integer
/// Lk up to rounding; with an open curve it is the real-valued Gauss integral (paper Fig. 6).
/// Throws CurvesIntersect when a segment pair touches or crosses.
double gauss_linking(const Points& a, bool a_closed, const Points& b, bool b_closed);

/// As gauss_linking(), and adds its gradient with respect to every vertex of `b` to `grad_b`
/// (resized to b.size()). Used for open finger curves b against a closed loop a.
double gauss_linking_gradient(const Points& a, bool a_closed, const Points& b, bool b_closed,
                              Points& grad_b);

/// Exact linking number of two closed polylines: the signed count of a's segments crossing a fan
/// triangulation of b (a surface bounded by b). Much cheaper than the Gauss sum and always an
/// integer; degenerate touches are resolved by a consistent symbolic tie-break. The curves are
/// assumed disjoint (use gauss_linking() to detect intersections).
int linking_number(const Points& a, const Points& b);

/// Virtual linking of a closed loop γ and an open finger curve α (eq. 2):
///   VLk(γ, α) = (1 − δ_α/|α̂|) · Lk(γ, α̂),
/// α̂ = α closed by the virtual cord from its last point to its first, δ_α = the cord length,
/// |α̂| = the length of α̂. The sign follows Lk(γ, α̂) and so depends on the loop's orientation.
struct VirtualLinking {
  double value = 0.0;          ///< VLk(γ, α)
  int closed_linking = 0;      ///< Lk(γ, α̂), exact
  double cord = 0.0;           ///< δ_α
  double closed_length = 0.0;  ///< |α̂|
  /// 1 − δ_α/|α̂|: how far the virtual cord is closed, in [0, 1).
  double closure() const { return 1.0 - cord / closed_length; }
};

VirtualLinking virtual_linking(const Points& loop, const Points& finger);

/// Gradient of VLk with respect to the finger's vertices (resized to finger.size()). Lk(γ, α̂) is
/// piecewise constant, so where it is defined the gradient is Lk · ∇(1 − δ_α/|α̂|): shortening
/// the cord, or lengthening the finger curve around the loop, raises |VLk|. Zero when Lk = 0.
void virtual_linking_gradient(const VirtualLinking& vlk, const Points& finger, Points& grad);

}  // namespace claspplan::servo
