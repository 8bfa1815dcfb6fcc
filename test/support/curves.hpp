// Curves with known linking for tests and benchmarks: circles, torus links, braid closures.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

namespace claspplan::test {

using Curve = std::vector<Eigen::Vector3d>;

constexpr double kPi = 3.14159265358979323846;

/// Circle of radius r in the plane through `centre` spanned by e1, e2 (counter-clockwise from e1
/// to e2), with n vertices.
inline Curve circle(const Eigen::Vector3d& centre, double r, const Eigen::Vector3d& e1,
                    const Eigen::Vector3d& e2, int n) {
  Curve c;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * kPi * i / n;
    c.push_back(centre + r * (std::cos(t) * e1 + std::sin(t) * e2));
  }
  return c;
}

/// Component j (0 or 1) of the torus link T(2, 2k): the curve θ = kφ + jπ on the torus with
/// radii R > r. Both components wind once around the z axis and k times around the tube, so
/// |Lk| = k.
inline Curve torus_link_component(int k, int j, int n, double R = 1.0, double r = 0.4) {
  Curve c;
  for (int i = 0; i < n; ++i) {
    const double phi = 2.0 * kPi * i / n;
    const double theta = k * phi + j * kPi;
    c.emplace_back((R + r * std::cos(theta)) * std::cos(phi),
                   (R + r * std::cos(theta)) * std::sin(phi), r * std::sin(theta));
  }
  return c;
}

/// The closure of a braid on `strands` strands, as closed polylines (one per component). The
/// word lists generators ±(i+1) for σ_i^{±1}, which swaps the strands at positions i and i+1; the
/// strand moving outward passes over for σ_i and under for σ_i^{-1}. Strand positions are radii
/// around the z axis and the braid runs around it once.
inline std::vector<Curve> braid_closure(int strands, const std::vector<int>& word,
                                        int samples_per_crossing = 16) {
  const int sectors = static_cast<int>(word.size());
  std::vector<int> position(strands);  // position of each strand label
  for (int s = 0; s < strands; ++s) position[s] = s;
  std::vector<Curve> pieces(strands);
  const auto radius = [](double p) { return 1.0 + 0.3 * p; };
  for (int s = 0; s < sectors; ++s) {
    const int g = std::abs(word[s]) - 1;
    const bool positive = word[s] > 0;
    for (int k = 0; k < samples_per_crossing; ++k) {
      const double t = static_cast<double>(k) / samples_per_crossing;
      const double phi = 2.0 * kPi * (s + t) / sectors;
      const double blend = 0.5 * (1.0 - std::cos(kPi * t));
      for (int label = 0; label < strands; ++label) {
        const int p = position[label];
        double rho = radius(p), z = 0.0;
        if (p == g || p == g + 1) {
          const bool outward = (p == g);
          rho = radius(outward ? g + blend : g + 1 - blend);
          z = ((outward == positive) ? 1.0 : -1.0) * 0.2 * std::sin(kPi * t);
        }
        pieces[label].emplace_back(rho * std::cos(phi), rho * std::sin(phi), z);
      }
    }
    for (int label = 0; label < strands; ++label) {
      if (position[label] == g) {
        position[label] = g + 1;
      } else if (position[label] == g + 1) {
        position[label] = g;
      }
    }
  }
  // After one turn, strand `label` continues as the strand that started at its end position.
  std::vector<Curve> components;
  std::vector<bool> used(strands, false);
  for (int start = 0; start < strands; ++start) {
    if (used[start]) continue;
    Curve c;
    for (int label = start; !used[label]; label = position[label]) {
      used[label] = true;
      c.insert(c.end(), pieces[label].begin(), pieces[label].end());
    }
    components.push_back(c);
  }
  return components;
}

inline Curve reversed(Curve c) {
  std::reverse(c.begin(), c.end());
  return c;
}

inline Curve transformed(const Curve& c, const Eigen::Isometry3d& T, double scale = 1.0) {
  Curve out;
  for (const auto& p : c) out.push_back(T * (scale * p));
  return out;
}

/// Splits every segment (the closing one too when `closed`) into `parts` equal pieces.
inline Curve subdivided(const Curve& c, bool closed, int parts) {
  Curve out;
  const std::size_t segments = closed ? c.size() : c.size() - 1;
  for (std::size_t i = 0; i < segments; ++i) {
    const auto& a = c[i];
    const auto& b = c[(i + 1) % c.size()];
    for (int k = 0; k < parts; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / parts));
  }
  if (!closed) out.push_back(c.back());
  return out;
}

inline Eigen::Isometry3d random_rigid_motion(std::mt19937_64& rng) {
  std::normal_distribution<double> n01;
  Eigen::Quaterniond q(n01(rng), n01(rng), n01(rng), n01(rng));
  q.normalize();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = Eigen::Vector3d(n01(rng), n01(rng), n01(rng)) * 3.0;
  return T;
}

}  // namespace claspplan::test
