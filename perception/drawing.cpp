#include "perception/drawing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/png_files.hpp"

namespace claspplan::perception {

void draw_object_model_png(const ObjectModel& model, const std::string& path, int width,
                           int height) {
  if (width < 100 || height < 100) throw std::invalid_argument("picture too small");
  // Orthographic view: from the first camera's direction, else an oblique view from the front left.
  Eigen::Matrix3d R;  // rows: screen right, screen down, away from the viewer
  if (!model.views.empty()) {
    R = model.views.front().camera.T_world_camera.linear().transpose();
  } else {
    const double az = -1.0, el = 0.55;
    const Eigen::Vector3d to_eye(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                 std::sin(el));
    const Eigen::Vector3d z = -to_eye;
    const Eigen::Vector3d y = (-Eigen::Vector3d::UnitZ() + z.z() * z).normalized();
    R.row(0) = y.cross(z);
    R.row(1) = y;
    R.row(2) = z;
  }
  const auto& pts = model.complex.points.empty() ? model.cloud : model.complex.points;
  std::vector<Eigen::Vector3d> s(pts.size());
  Eigen::AlignedBox2d box;
  for (size_t i = 0; i < pts.size(); ++i) {
    s[i] = R * pts[i];
    box.extend(s[i].head<2>());
  }
  const int caption = 30 + 18 * static_cast<int>(std::min<size_t>(model.loops.size(), 8) + 1);
  const double avail_w = width - 40.0, avail_h = height - 40.0 - caption;
  const double scale = box.isEmpty() ? 1.0
                                     : std::min(avail_w / std::max(box.sizes().x(), 1e-9),
                                                avail_h / std::max(box.sizes().y(), 1e-9));
  const Eigen::Vector2d centre =
      box.isEmpty() ? Eigen::Vector2d(Eigen::Vector2d::Zero()) : Eigen::Vector2d(box.center());
  auto px = [&](const Eigen::Vector3d& q) {
    return cv::Point2d(width / 2.0 + scale * (q.x() - centre.x()),
                       20.0 + avail_h / 2.0 + scale * (q.y() - centre.y()));
  };
  const int sub = 4;  // sub-pixel bits for anti-aliased drawing
  auto fp = [&](const cv::Point2d& p) { return cv::Point(cvRound(p.x * 16), cvRound(p.y * 16)); };
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto& k = model.complex;

  // Triangles back to front, shaded by how much they face the viewer.
  std::vector<int> order(k.triangles.size());
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> depth(k.triangles.size());
  for (size_t t = 0; t < k.triangles.size(); ++t) {
    const auto v = k.triangle_vertices(static_cast<int>(t));
    depth[t] = s[v[0]].z() + s[v[1]].z() + s[v[2]].z();
  }
  std::sort(order.begin(), order.end(), [&](int a, int b) { return depth[a] > depth[b]; });
  std::vector<char> in_triangle(k.edges.size(), 0);
  for (const auto& t : k.triangles)
    for (int e : t) in_triangle[e] = 1;
  for (int t : order) {
    const auto v = k.triangle_vertices(t);
    const Eigen::Vector3d nrm = (s[v[1]] - s[v[0]]).cross(s[v[2]] - s[v[0]]);
    const double facing = nrm.norm() > 0 ? std::abs(nrm.z()) / nrm.norm() : 0.0;
    const int g = static_cast<int>(150 + 90 * facing);
    const cv::Point poly[3] = {fp(px(s[v[0]])), fp(px(s[v[1]])), fp(px(s[v[2]]))};
    cv::fillConvexPoly(img, poly, 3, cv::Scalar(g, g, g), cv::LINE_AA, sub);
    cv::polylines(img, std::vector<cv::Point>(poly, poly + 3), true,
                  cv::Scalar(g - 60, g - 60, g - 60), 1, cv::LINE_AA, sub);
  }
  for (size_t e = 0; e < k.edges.size(); ++e) {
    if (in_triangle[e]) continue;
    cv::line(img, fp(px(s[k.edges[e][0]])), fp(px(s[k.edges[e][1]])), cv::Scalar(110, 110, 110), 1,
             cv::LINE_AA, sub);
  }
  // Loops on top: others blue, the best claspable one thick red.
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < model.loops.size(); ++i) {
      const Loop& l = model.loops[i];
      const bool best = i == 0 && l.claspable;
      if (best != (pass == 1)) continue;
      std::vector<cv::Point> line;
      for (const auto& p : l.points) line.push_back(fp(px(R * p)));
      const cv::Scalar colour = best          ? cv::Scalar(0, 0, 230)
                                : l.claspable ? cv::Scalar(200, 120, 0)
                                              : cv::Scalar(220, 160, 60);
      cv::polylines(img, line, true, colour, best ? 4 : 2, cv::LINE_AA, sub);
    }
  }
  // Caption.
  char buf[256];
  int y = height - caption + 18;
  std::snprintf(buf, sizeof buf,
                "K_d: %d points, %zu edges, %zu triangles, d = %.4f m; beta1 = %d%s",
                k.vertex_count(), k.edges.size(), k.triangles.size(), model.d, model.beta1,
                model.loops.empty() ? " (no loops)" : "");
  cv::putText(img, buf, cv::Point(12, y), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  for (size_t i = 0; i < model.loops.size() && i < 8; ++i) {
    const Loop& l = model.loops[i];
    y += 18;
    std::snprintf(buf, sizeof buf, "#%d %s  length %.3f m  %s", l.rank,
                  i == 0 && l.claspable ? "(red)" : "(blue)", l.length, l.reason.c_str());
    cv::putText(img, std::string(buf).substr(0, 140), cv::Point(12, y), cv::FONT_HERSHEY_SIMPLEX,
                0.42, i == 0 && l.claspable ? cv::Scalar(0, 0, 200) : cv::Scalar(150, 90, 0), 1,
                cv::LINE_AA);
  }
  write_png(path, img);
}

void draw_sensed_space_png(const SensedSpace& space, const Eigen::Vector3d& centre,
                           const std::vector<Eigen::Vector3d>& loop, const std::string& caption,
                           const std::string& path, const ViewSuggestion* view,
                           const SensedSpace* finer) {
  if (space.empty()) throw std::invalid_argument("sensed space: nothing to draw (no sensor)");
  if (finer && finer->empty()) finer = nullptr;
  constexpr int kPanel = SensedPictureLayout::panel, kGap = SensedPictureLayout::gap,
                kTop = SensedPictureLayout::title;
  const int bottom = view ? 78 : 56;
  cv::Mat img(kTop + kPanel + bottom, 3 * kPanel + 4 * kGap, CV_8UC3, cv::Scalar(255, 255, 255));
  const Eigen::AlignedBox3d& box = space.region();
  const double side = box.sizes().maxCoeff();
  const double scale = kPanel / side;  // pixels per metre, the same in every panel
  // Each panel: screen x along axis a, screen y down along -b, the slice at centre[c].
  const std::array<std::array<int, 3>, 3> axes{{{0, 2, 1}, {1, 2, 0}, {0, 1, 2}}};
  const char* names[] = {"x-z slice (y = %.2f m)", "y-z slice (x = %.2f m)",
                         "x-y slice (z = %.2f m)"};
  const cv::Scalar colour[] = {cv::Scalar(60, 150, 245), cv::Scalar(245, 245, 245),
                               cv::Scalar(120, 50, 20)};  // unknown, free, occupied (BGR)
  for (int panel = 0; panel < 3; ++panel) {
    const int a = axes[panel][0], b = axes[panel][1], c = axes[panel][2];
    const int x0 = kGap + panel * (kPanel + kGap), y0 = kTop;
    const Eigen::Vector2d lo(box.min()[a], box.min()[b]);
    for (int py = 0; py < kPanel; ++py)
      for (int px = 0; px < kPanel; ++px) {
        Eigen::Vector3d p = centre;
        p[a] = lo.x() + (px + 0.5) / scale;
        p[b] = lo.y() + (kPanel - py - 0.5) / scale;
        cv::Vec3b& out = img.at<cv::Vec3b>(y0 + py, x0 + px);
        if (!box.contains(p)) {
          out = cv::Vec3b(200, 200, 200);
          continue;
        }
        const cv::Scalar& k = colour[static_cast<int>(sensed_at(space, finer, p))];
        out =
            cv::Vec3b(static_cast<uchar>(k[0]), static_cast<uchar>(k[1]), static_cast<uchar>(k[2]));
      }
    const auto screen = [&](const Eigen::Vector3d& q) {
      return cv::Point(x0 + static_cast<int>((q[a] - lo.x()) * scale),
                       y0 + kPanel - static_cast<int>((q[b] - lo.y()) * scale));
    };
    if (finer && finer->region().min()[c] <= centre[c] && centre[c] <= finer->region().max()[c])
      cv::rectangle(img, screen(finer->region().min()), screen(finer->region().max()),
                    cv::Scalar(130, 130, 130), 1);
    for (std::size_t i = 0; i < loop.size(); ++i)
      cv::line(img, screen(loop[i]), screen(loop[(i + 1) % loop.size()]), cv::Scalar(0, 0, 220), 2,
               cv::LINE_AA);
    if (view) {  // the camera usually stands outside the region: its line clipped to the panel
      const cv::Rect inside(x0, y0, kPanel, kPanel);
      cv::Point from = screen(view->position), to = screen(view->target);
      const cv::Point dot = to;
      if (cv::clipLine(inside, from, to))
        cv::line(img, from, to, cv::Scalar(0, 170, 0), 2, cv::LINE_AA);
      if (inside.contains(dot)) cv::circle(img, dot, 5, cv::Scalar(0, 170, 0), cv::FILLED);
    }
    char buf[96];
    std::snprintf(buf, sizeof buf, names[panel], centre[c]);
    cv::putText(img, buf, cv::Point(x0, 17), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1,
                cv::LINE_AA);
  }
  const auto n = space.counts();
  const double all = static_cast<double>(n[0] + n[1] + n[2]);
  char buf[256];
  char finer_text[48] = "";
  if (finer)
    std::snprintf(finer_text, sizeof finer_text, ", %.1f mm in the box",
                  1000.0 * finer->resolution());
  std::snprintf(buf, sizeof buf,
                "free (white) %.0f%%, occupied (blue) %.0f%%, unknown (orange) %.0f%%: %.1f mm "
                "voxels%s; grey: outside the region, free to the robot",
                100.0 * n[1] / all, 100.0 * n[2] / all, 100.0 * n[0] / all,
                1000.0 * space.resolution(), finer_text);
  cv::putText(img, buf, cv::Point(kGap, kTop + kPanel + 20), cv::FONT_HERSHEY_SIMPLEX, 0.42,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  cv::putText(img, caption.substr(0, 150), cv::Point(kGap, kTop + kPanel + 42),
              cv::FONT_HERSHEY_SIMPLEX, 0.42, cv::Scalar(0, 0, 160), 1, cv::LINE_AA);
  if (view)
    cv::putText(img, "next best view (green): " + view_text(*view),
                cv::Point(kGap, kTop + kPanel + 64), cv::FONT_HERSHEY_SIMPLEX, 0.42,
                cv::Scalar(0, 120, 0), 1, cv::LINE_AA);
  write_png(path, img);
}

}  // namespace claspplan::perception
