// The rules that read a hand's geometry at its open pre-shape for the draft: which finger is the
// thumb, how it turns to oppose the fingers, which way each joint closes, where fingers start,
// v_fwd, v_swd and the finger curves.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "robots/description_draft_detail.hpp"
#include "robots/hand_size.hpp"
#include "robots/kinematics.hpp"

namespace claspplan::robots::draft_detail {
namespace {

// A unit direction with components under 0.02 set to 0 (an axis of the link, as URDFs mostly
// have it, rather than one a few tenths of a degree off).
Eigen::Vector3d snapped(Eigen::Vector3d v) {
  v.normalize();
  for (int i = 0; i < 3; ++i)
    if (std::abs(v[i]) < 0.02) v[i] = 0.0;
  return v.normalized();
}

bool mentions_thumb(const FingerDraft& f) {
  for (const auto& names : {f.links, f.joints})
    for (std::string n : names) {
      std::transform(n.begin(), n.end(), n.begin(),
                     [](unsigned char c) { return std::tolower(c); });
      if (n.find("thumb") != std::string::npos) return true;
    }
  return false;
}

// How far the points are from lying in a row: the RMS distance from their least-squares line.
double off_line(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p / static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  return std::sqrt(std::max(0.0, es.eigenvalues()(0) + es.eigenvalues()(1)) /
                   static_cast<double>(points.size()));
}

// The finger set apart: named so; else, of four or more, the one without which the others' bases
// lie most nearly in a row (a hand's fingers side by side); of three, the one farthest from the
// other two (two fingers facing one); of two, the second (they face each other).
int find_thumb(const std::vector<FingerDraft>& fingers, const std::vector<Eigen::Vector3d>& base,
               std::vector<std::string>& guesses) {
  for (std::size_t f = 0; f < fingers.size(); ++f)
    if (mentions_thumb(fingers[f])) {
      guesses.push_back("thumb: the finger whose links or joints are named 'thumb'");
      return static_cast<int>(f);
    }
  const int n = static_cast<int>(fingers.size());
  if (n == 2) {
    guesses.push_back("thumb: of two fingers, the second (they face each other)");
    return 1;
  }
  int best = 0;
  double best_score = std::numeric_limits<double>::infinity();
  for (int f = 0; f < n; ++f) {
    std::vector<Eigen::Vector3d> others;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int g = 0; g < n; ++g)
      if (g != f) {
        others.push_back(base[g]);
        mean += base[g] / (n - 1);
      }
    const double score = n >= 4 ? off_line(others) : -(base[f] - mean).norm();
    if (score < best_score) {
      best_score = score;
      best = f;
    }
  }
  guesses.push_back("thumb: the finger of " + fingers[best].links.front() +
                    (n >= 4 ? ", without which the other fingers' bases lie in a row"
                            : ", whose base lies farthest from the other two"));
  return best;
}

Eigen::Vector3d position(const RobotModel& m, const RobotData& data, const CurvePoint& p) {
  return point_position(data, LinkPoint{m.link_index(p.link), p.xyz});
}

// The direction from finger f's tip toward the finger(s) it closes on, across its own length.
Eigen::Vector3d toward_opposite(const Eigen::Vector3d& base, const Eigen::Vector3d& tip,
                                const Eigen::Vector3d& opposite) {
  const Eigen::Vector3d along =
      (tip - base).norm() > 1e-6 ? (tip - base).normalized() : Eigen::Vector3d::Zero();
  Eigen::Vector3d toward = opposite - tip;
  const Eigen::Vector3d across = toward - toward.dot(along) * along;
  if (across.norm() > 1e-3) toward = across;
  return toward.norm() > 1e-9 ? toward.normalized() : Eigen::Vector3d::UnitX();
}

// The fingertip at the pose in `data`: the far end of the last link's shapes along the finger
// (from the previous link's origin through the last one's), else the last link's origin. Taken
// at the open hand: a phalanx's frame may turn away from the bone at other joint values.
CurvePoint tip_point(const RobotModel& m, const RobotData& data, const FingerDraft& f) {
  const int leaf = m.link_index(f.links.back());
  const Eigen::Isometry3d& pose = data.link_poses[leaf];
  const int parent = m.links[leaf].parent;
  Eigen::Vector3d u = pose.translation() - data.link_poses[parent].translation();
  if (u.norm() < 1e-6)
    u = pose.translation() - data.link_poses[m.link_index(f.links[0])].translation();
  u = u.norm() > 1e-6 ? u.normalized() : pose.linear().col(2);
  double reach = 0.0;
  for (int s : m.links[leaf].shapes) {
    const CollisionShape& shape = m.shapes[s];
    const Eigen::AlignedBox3d box = shape_bounds(shape);
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
      reach = std::max(reach, (pose.linear() * (shape.origin * corner)).dot(u));
    }
  }
  return {f.links.back(), pose.linear().transpose() * (reach * u), reach > 1e-4};
}

// The open hand as the draft sees it: each finger's base and tip at the pre-shape q.
struct OpenHand {
  const RobotModel& m;
  Eigen::VectorXd q;  // the arm's home and the hand's open pre-shape (the thumb turned)
  int thumb = -1;
  std::vector<Eigen::Vector3d> base, tip;
  mutable RobotData probe;

  OpenHand(const RobotModel& model, Draft& d) : m(model), q(model.home), probe(model) {
    open_at(q, d);
  }
  // Sets the pre-shape and the fingers' tips there.
  void open_at(const Eigen::VectorXd& at, Draft& d) {
    q = at;
    base.clear();
    tip.clear();
    forward_kinematics(m, q, probe);
    for (FingerDraft& f : d.fingers) {
      f.tip = tip_point(m, probe, f);
      base.push_back(probe.link_poses[m.link_index(f.links.front())].translation());
      tip.push_back(position(m, probe, f.tip));
    }
  }
  Eigen::Vector3d tip_at(const FingerDraft& f, const Eigen::VectorXd& at) const {
    forward_kinematics(m, at, probe);
    return position(m, probe, f.tip);
  }
  // The mean tip of the fingers other than the thumb.
  Eigen::Vector3d finger_tips() const {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t f = 0; f < tip.size(); ++f)
      if (static_cast<int>(f) != thumb) mean += tip[f] / static_cast<double>(tip.size() - 1);
    return mean;
  }
  // Finger f's tip velocity for joint qi at `at`, as the cosine with the direction toward the
  // finger(s) it closes on (0 when the joint does not move it).
  double toward_cosine(const Draft& d, int f, int qi, const Eigen::VectorXd& at) const {
    const FingerDraft& finger = d.fingers[f];
    const Eigen::Vector3d t = tip_at(finger, at);
    const Eigen::Vector3d toward =
        toward_opposite(base[f], t, f == thumb ? finger_tips() : tip[thumb]);
    Eigen::VectorXd hi = at, lo = at;
    hi[qi] = std::min(hi[qi] + 1e-3, m.joints[qi].upper);
    lo[qi] = std::max(lo[qi] - 1e-3, m.joints[qi].lower);
    if (!(hi[qi] > lo[qi])) return 0.0;
    const Eigen::Vector3d v = (tip_at(finger, hi) - tip_at(finger, lo)) / (hi[qi] - lo[qi]);
    return v.norm() > 1e-6 ? v.dot(toward) / v.norm() : 0.0;
  }
};

// A joint closes its finger when it moves the tip mostly toward the opposite finger(s) (+1 or -1
// the way it does). Else its range decides: a finger flexes far and extends little (an Allegro
// joint from -0.3 to 1.7 rad closes with +), while an abduction swings about as far either way
// (0: it stays at its open value).
int closing_direction(const OpenHand& hand, const Draft& d, int f, int qi) {
  const double c = hand.toward_cosine(d, f, qi, hand.q);
  if (std::abs(c) >= 0.4) return c > 0 ? 1 : -1;
  const Joint& j = hand.m.joints[qi];
  const double up = j.upper - hand.q[qi], down = hand.q[qi] - j.lower;
  if (up >= 2.0 * down && up > 0) return 1;
  if (down >= 2.0 * up && down > 0) return -1;
  return 0;
}

// A thumb of three or more joints turns on its first one to oppose the fingers (an Allegro's, a
// human's): that joint is held where the thumb points most toward the side of the palm the
// fingers close to. Returns the joint held, or -1.
int turn_thumb(OpenHand& hand, Draft& d, const Eigen::Vector3d& fingers_motion,
               std::vector<std::string>& guesses) {
  const FingerDraft& thumb = d.fingers[hand.thumb];
  if (thumb.joints.size() < 3 || fingers_motion.norm() < 1e-9) return -1;
  const int turn = hand.m.joint_index(thumb.joints.front());
  const Eigen::Vector3d front = fingers_motion.normalized();
  const auto facing = [&](const Eigen::VectorXd& at) {
    const Eigen::Vector3d along = hand.tip_at(thumb, at) - hand.base[hand.thumb];
    return along.norm() > 1e-9 ? along.dot(front) / along.norm() : 0.0;
  };
  const Joint& j = hand.m.joints[turn];
  const double lo = std::max(j.lower, -M_PI), hi = std::min(j.upper, M_PI);
  double best = facing(hand.q) + 0.1, value = hand.q[turn];  // worth turning for a clear gain
  for (int k = 0; k <= 16; ++k) {
    Eigen::VectorXd at = hand.q;
    at[turn] = lo + k / 16.0 * (hi - lo);
    const double score = facing(at);
    if (score > best) {
      best = score;
      value = at[turn];
    }
  }
  if (value == hand.q[turn]) return -1;
  hand.q[turn] = value;
  hand.tip[hand.thumb] = hand.tip_at(thumb, hand.q);
  for (JointDraft& jd : d.hand)
    if (jd.name == thumb.joints.front()) jd.open = value;
  guesses.push_back("thumb: " + thumb.joints.front() + " held at " + draft_number(value) +
                    " rad, where the thumb points most to the side the fingers close to");
  return turn;
}

// Closing directions of finger f's joints (`held`: none); a joint that closes from 0 with no room
// (a gripper closed at 0) opens at its other limit. Returns the tip's motion as it closes.
Eigen::Vector3d set_closing(const OpenHand& hand, Draft& d, int f, int held) {
  Eigen::VectorXd closed = hand.q;
  for (const std::string& name : d.fingers[f].joints) {
    const int qi = hand.m.joint_index(name);
    const int closing = qi == held ? 0 : closing_direction(hand, d, f, qi);
    for (JointDraft& j : d.hand) {
      if (j.name != name) continue;
      j.closing = closing;
      const double room = closing > 0 ? j.upper - j.open : j.open - j.lower;
      if (closing != 0 && room < 0.2 * (j.upper - j.lower))
        j.open = closing > 0 ? j.lower : j.upper;
    }
    closed[qi] += 1e-3 * closing;
  }
  return hand.tip_at(d.fingers[f], hand.m.clamp(closed)) - hand.tip[f];
}

// Thicker than this, a link is a palm, a knuckle or a thumb's base rather than a finger (m).
constexpr double kThickFinger = 0.04;

// A finger's links start where it closes: a knuckle turned by an abduction or a thumb's base
// stays beside the palm, outside any hole (and would count as finger thickness).
void trim_finger_links(const RobotModel& m, Draft& d) {
  for (FingerDraft& f : d.fingers) {
    std::size_t first = 0;
    for (; first + 1 < f.links.size(); ++first) {
      const Link& link = m.links[m.link_index(f.links[first])];
      const auto closes = [&](const JointDraft& j) {  // link's joint, or the one it mimics
        return link.q_index >= 0 && j.name == m.joints[link.q_index].name && j.closing;
      };
      double thickness = 0.0;
      for (int s : link.shapes) thickness = std::max(thickness, cross_section(m.shapes[s]));
      if (std::any_of(d.hand.begin(), d.hand.end(), closes) && thickness <= kThickFinger) break;
    }
    f.links.erase(f.links.begin(), f.links.begin() + static_cast<std::ptrdiff_t>(first));
  }
}

// v_fwd along the straight fingers, v_swd normal to the plane their tips close in, and one curve
// per finger against the thumb (without points that coincide at the open hand).
void frame_and_curves(const OpenHand& hand, Draft& d, Eigen::Vector3d motion) {
  const RobotModel& m = hand.m;
  RobotData data(m);
  forward_kinematics(m, hand.q, data);
  const int root = m.link_index(d.base_link), n = static_cast<int>(d.fingers.size());
  const Eigen::Matrix3d to_root = data.link_poses[root].linear().transpose();
  Eigen::Vector3d fwd = Eigen::Vector3d::Zero();
  for (int f = 0; f < n; ++f)
    if (f != hand.thumb && (hand.tip[f] - hand.base[f]).norm() > 1e-6)
      fwd += (hand.tip[f] - hand.base[f]).normalized();
  fwd = fwd.norm() > 1e-9 ? fwd.normalized() : data.link_poses[root].linear().col(2);
  motion -= motion.dot(fwd) * fwd;
  Eigen::Vector3d swd = fwd.cross(motion);
  if (swd.norm() < 1e-12) swd = fwd.unitOrthogonal();
  d.v_fwd = snapped(to_root * fwd);
  swd = to_root * swd;
  d.v_swd = snapped(swd - swd.dot(d.v_fwd) * d.v_fwd);
  d.v_swd = (d.v_swd - d.v_swd.dot(d.v_fwd) * d.v_fwd).normalized();
  d.curves.clear();
  const Eigen::Vector3d origin = data.link_poses[root].translation();
  const FingerDraft& thumb = d.fingers[hand.thumb];
  for (int f = 0; f < n; ++f) {
    if (f == hand.thumb) continue;
    std::vector<CurvePoint> points;
    Eigen::Vector3d last(NAN, NAN, NAN);
    const auto add = [&](const CurvePoint& p) {
      const Eigen::Vector3d at = position(m, data, p);
      if ((at - last).norm() < 1e-3) return;
      points.push_back(p);
      last = at;
    };
    add(d.fingers[f].tip);
    for (auto l = d.fingers[f].links.rbegin(); l != d.fingers[f].links.rend(); ++l) add({*l});
    add({d.base_link, to_root * (0.5 * (hand.base[f] + hand.base[hand.thumb]) - origin), true});
    for (const std::string& l : thumb.links) add({l});
    add(thumb.tip);
    d.curves.emplace_back(d.fingers[f].name + "-thumb", points);
  }
}

}  // namespace

void shape_hand(Draft& d, const RobotModel& m, std::vector<std::string>& guesses) {
  OpenHand hand(m, d);
  hand.thumb = find_thumb(d.fingers, hand.base, guesses);
  for (FingerDraft& f : d.fingers) f.thumb = false;
  d.fingers[hand.thumb].thumb = true;
  d.fingers[hand.thumb].name = "thumb";
  Eigen::Vector3d motion = Eigen::Vector3d::Zero();  // the fingers' tips as they close
  int held = -1;
  // A second pass when a joint opens at its other limit (a hand closed at 0, as NAO's and
  // Romeo's are): the directions and tips are read again at the open hand.
  for (int pass = 0; pass < 2; ++pass) {
    motion.setZero();
    for (int f = 0; f < static_cast<int>(d.fingers.size()); ++f)
      if (f != hand.thumb) motion += set_closing(hand, d, f, -1);
    if (pass == 0) held = turn_thumb(hand, d, motion, guesses);
    set_closing(hand, d, hand.thumb, held);
    Eigen::VectorXd open = hand.q;
    for (const JointDraft& j : d.hand) open[m.joint_index(j.name)] = j.open;
    if (pass == 1 || open.isApprox(hand.q)) break;
    hand.open_at(open, d);
  }
  trim_finger_links(m, d);
  frame_and_curves(hand, d, motion);
}

}  // namespace claspplan::robots::draft_detail
