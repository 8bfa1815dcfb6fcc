// A clasp target (paper Sec. IV-B): a point on an object's loop and the loop's unit tangent there.
// Perception places them on the chosen loop; the clasp controller's alignment task aims at them.
#pragma once

#include <Eigen/Core>

namespace claspplan {

struct ClaspTarget {
  Eigen::Vector3d point;
  Eigen::Vector3d tangent;  ///< unit
};

}  // namespace claspplan
