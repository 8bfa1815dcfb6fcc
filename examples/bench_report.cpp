#include "examples/bench_report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "core/input_error.hpp"
#include "core/png_files.hpp"
#include "examples/bench_suite.hpp"

namespace claspplan::cli {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// JSON has no NaN: a missing value is null.
nlohmann::json number(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nullptr;
}
double number_from(const nlohmann::json& j, const char* key) {
  const auto& v = j.at(key);
  return v.is_null() ? kNaN : v.get<double>();
}

std::string fixed(double x, int digits) {
  if (!std::isfinite(x)) return "-";
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

std::string csv_text(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  if (!f) throw std::runtime_error("cannot write " + path.string());
}

void write_png(const std::filesystem::path& path, const cv::Mat& image) {
  claspplan::write_png(path.string(), image);
}

const cv::Scalar kGreen(60, 160, 60), kRed(60, 60, 200), kGrey(120, 120, 120), kBlack(0, 0, 0);

template <class Keep>
std::vector<BenchRecord> select(const std::vector<BenchRecord>& records, Keep keep) {
  std::vector<BenchRecord> out;
  std::copy_if(records.begin(), records.end(), std::back_inserter(out), keep);
  return out;
}

// TS-RRT's runs at the scenario's own tolerance, those of the tolerance sweep, a baseline's.
std::vector<BenchRecord> main_runs(const std::vector<BenchRecord>& records) {
  return select(records,
                [](const BenchRecord& r) { return !(r.tolerance > 0) && r.method.empty(); });
}

std::vector<BenchRecord> sweep_runs(const std::vector<BenchRecord>& records) {
  return select(records, [](const BenchRecord& r) { return r.tolerance > 0 && r.method.empty(); });
}

std::vector<BenchRecord> method_runs(const std::vector<BenchRecord>& records,
                                     const std::string& method) {
  return select(records, [&](const BenchRecord& r) { return r.method == method; });
}

std::vector<std::string> methods(const std::vector<BenchRecord>& records) {
  std::vector<std::string> out;
  for (const auto& r : records)
    if (!r.method.empty() && std::find(out.begin(), out.end(), r.method) == out.end())
      out.push_back(r.method);
  return out;
}

// TS-RRT's main run of the baseline run's scenario and seed, or nullptr.
const BenchRecord* ours_for(const std::vector<BenchRecord>& main, const BenchRecord& r) {
  for (const auto& m : main)
    if (m.name == r.name && m.seed == r.seed) return &m;
  return nullptr;
}

// Planning seconds per scenario: TS-RRT's bar (left) beside the baseline's (right, outlined);
// green verified, red not.
cv::Mat method_time(const std::vector<BenchRecord>& main, const std::vector<BenchRecord>& runs,
                    const std::string& method) {
  const int height = 360, margin = 50;
  const int pair = std::clamp(900 / std::max<int>(1, static_cast<int>(runs.size())), 4, 30);
  const int width = 2 * margin + pair * static_cast<int>(runs.size());
  cv::Mat img(height, std::max(width, 520), CV_8UC3, cv::Scalar(255, 255, 255));
  double top = 1e-3;
  for (const auto& r : runs) {
    top = std::max(top, r.seconds);
    if (const BenchRecord* m = ours_for(main, r)) top = std::max(top, m->seconds);
  }
  const int base = height - margin, span = height - 2 * margin, half = pair / 2;
  cv::line(img, cv::Point(margin, base), cv::Point(img.cols - margin, base), kBlack);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const int x = margin + static_cast<int>(i) * pair;
    if (const BenchRecord* m = ours_for(main, runs[i])) {
      const int h = static_cast<int>(m->seconds / top * span);
      cv::rectangle(img, cv::Point(x + 1, base - h), cv::Point(x + half - 1, base),
                    m->verified ? kGreen : kRed, cv::FILLED);
    }
    const int h = static_cast<int>(runs[i].seconds / top * span);
    cv::rectangle(img, cv::Point(x + half, base - h), cv::Point(x + pair - 2, base),
                  runs[i].verified ? kGreen : kRed, 1);
  }
  cv::putText(img,
              "seconds per scenario (max " + fixed(top, 2) + " s): TS-RRT filled, " + method +
                  " outlined; green verified",
              cv::Point(10, 25), cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack);
  return img;
}

// TS-RRT against a baseline on the same scenarios and seeds.
std::string method_markdown(const std::vector<BenchRecord>& main,
                            const std::vector<BenchRecord>& runs, const std::string& method) {
  int success = 0, verified = 0, ours_success = 0, ours_verified = 0, paired = 0;
  std::vector<double> seconds, ours_seconds;
  for (const auto& r : runs) {
    success += r.success;
    verified += r.verified;
    if (r.verified) seconds.push_back(r.seconds);
    if (const BenchRecord* m = ours_for(main, r)) {
      ++paired;
      ours_success += m->success;
      ours_verified += m->verified;
      if (m->verified) ours_seconds.push_back(m->seconds);
    }
  }
  std::ostringstream md;
  md << "\n## TS-RRT against the baseline " << method << "\n\n"
     << "The same scenarios and seeds; seconds of planning with the clasp checks (perception "
        "excluded), medians over the verified runs.\n\n"
     << "| method | runs | success | verified clasps | median s |\n|---|---|---|---|---|\n"
     << "| TS-RRT | " << paired << " | " << ours_success << " | " << ours_verified << " | "
     << fixed(median(ours_seconds), 2) << " |\n"
     << "| " << method << " | " << runs.size() << " | " << success << " | " << verified << " | "
     << fixed(median(seconds), 2) << " |\n\n"
     << "Success: a clasp found (grasp_rrt: a grasp scored). Verified clasps among the "
        "successes: TS-RRT "
     << ours_verified << " of " << ours_success << ", " << method << " " << verified << " of "
     << success << ". Median time ratio (" << method
     << " / TS-RRT): " << fixed(median(seconds) / median(ours_seconds), 1) << ".\n\n"
     << "| scenario | seed | TS-RRT | " << method << " | " << method
     << ": reason when not verified |\n|---|---|---|---|---|\n";
  const auto cell = [](const BenchRecord& r) {
    return (r.verified ? "verified " : "no, ") + fixed(r.seconds, 2) + " s";
  };
  for (const auto& r : runs) {
    const BenchRecord* m = ours_for(main, r);
    md << "| " << r.name << " | " << r.seed << " | " << (m ? cell(*m) : "-") << " | " << cell(r)
       << " | " << (r.verified ? "" : r.reason.substr(0, r.reason.find(':', 25))) << " |\n";
  }
  md << "\nPlot: " << method << "_time.png.\n";
  return md.str();
}

// Paper Fig. 8 as numbers: the closed hand's mean VLk per goal tolerance, one dot per run (spread
// sideways), secure clasps green, others red; a black bar at each tolerance's median.
cv::Mat tolerance_sweep(const std::vector<BenchRecord>& runs) {
  std::map<double, std::vector<const BenchRecord*>> by;
  for (const auto& r : runs) by[r.tolerance].push_back(&r);
  const int height = 420, margin = 60, column = 140;
  const int width = 2 * margin + column * static_cast<int>(by.size());
  cv::Mat img(height, std::max(width, 420), CV_8UC3, cv::Scalar(255, 255, 255));
  double top = 1.0;
  for (const auto& r : runs)
    if (std::isfinite(r.final_linking)) top = std::max(top, std::ceil(2.0 * r.final_linking) / 2.0);
  const int base = height - margin, span = height - 2 * margin;
  const auto y_of = [&](double v) {
    return base - static_cast<int>(std::clamp(v / top, 0.0, 1.0) * span);
  };
  cv::rectangle(img, cv::Point(margin, y_of(top)), cv::Point(img.cols - margin, base), kBlack);
  for (double t = 0.0; t <= top + 1e-9; t += 0.25) {
    cv::line(img, cv::Point(margin - 4, y_of(t)), cv::Point(margin, y_of(t)), kBlack);
    cv::putText(img, fixed(t, 2), cv::Point(10, y_of(t) + 4), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                kBlack);
  }
  int c = 0;
  for (const auto& [tolerance, list] : by) {
    const int x0 = margin + c++ * column;
    cv::putText(img, "tolerance " + fixed(tolerance, 2), cv::Point(x0 + 20, base + 25),
                cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack);
    std::vector<double> values;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const BenchRecord& r = *list[i];
      if (!std::isfinite(r.final_linking)) continue;
      values.push_back(r.final_linking);
      const int x = x0 + 20 + static_cast<int>((i * 97) % 100);
      cv::circle(img, cv::Point(x, y_of(r.final_linking)), 4, r.verified ? kGreen : kRed,
                 cv::FILLED, cv::LINE_AA);
    }
    if (!values.empty()) {
      const int y = y_of(median(values));
      cv::line(img, cv::Point(x0 + 10, y), cv::Point(x0 + column - 10, y), kBlack, 2);
    }
  }
  cv::putText(img, "final mean VLk (fingers closed) per goal tolerance; green secure, bar median",
              cv::Point(10, 25), cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack);
  return img;
}

// Paper Sec. V-C: per tolerance, how many runs reached it, the final VLk, the secure clasps.
std::string sweep_markdown(const std::vector<BenchRecord>& runs) {
  struct Column {
    int runs = 0, reached = 0, secure = 0;
    std::vector<double> linking;
  };
  std::map<double, Column> columns;
  std::map<std::string, std::map<double, const BenchRecord*>> cells;
  for (const auto& r : runs) {
    Column& col = columns[r.tolerance];
    ++col.runs;
    if (std::isfinite(r.final_linking)) {
      ++col.reached;
      col.linking.push_back(r.final_linking);
    }
    col.secure += r.verified;
    cells[r.name][r.tolerance] = &r;
  }
  std::ostringstream md;
  md << "\n## Virtual-linking tolerance (paper Sec. V-C, Fig. 8)\n\n"
     << "The tree's goal tolerance set to each value, the first goal node taken (no check in the "
        "search), the fingers closed (again after an approach to contact, then after the "
        "controller went on to the linking goal, when that clasp is refused or insecure), then "
        "the secure-clasp check.\n\n"
     << "| tolerance | runs | goal node reached | median final VLk | lowest final VLk | secure "
        "clasps |\n|---|---|---|---|---|---|\n";
  for (const auto& [tolerance, col] : columns) {
    const double lowest =
        col.linking.empty() ? kNaN : *std::min_element(col.linking.begin(), col.linking.end());
    md << "| " << fixed(tolerance, 2) << " | " << col.runs << " | " << col.reached << " | "
       << fixed(median(col.linking), 2) << " | " << fixed(lowest, 2) << " | " << col.secure << "/"
       << col.runs << " |\n";
  }
  md << "\nPer scenario (final VLk; S secure, - not):\n\n| scenario |";
  for (const auto& column : columns) md << " " << fixed(column.first, 2) << " |";
  md << "\n|---|";
  for (std::size_t i = 0; i < columns.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& [name, row] : cells) {
    md << "| " << name << " |";
    for (const auto& column : columns) {
      const auto it = row.find(column.first);
      if (it == row.end() || !std::isfinite(it->second->final_linking)) {
        md << " - |";
      } else {
        md << " " << fixed(it->second->final_linking, 2) << (it->second->verified ? " S" : "")
           << " |";
      }
    }
    md << "\n";
  }
  md << "\nPlot: tolerance_sweep.png.\n";
  return md.str();
}

// Paper Fig. 6: min vs max over the finger curves of the final pose, open-curve |Lk| (circles)
// and VLk (crosses); verified clasps green, others red.
cv::Mat linking_scatter(const std::vector<BenchRecord>& records) {
  const int size = 520, margin = 60, side = size - 2 * margin;
  // Open-curve |Lk| can pass 1: the axes reach the largest value, in steps of 0.5.
  double top = 1.0;
  for (const auto& r : records)
    for (double v : {r.max_open_linking, r.max_virtual_linking})
      if (std::isfinite(v)) top = std::max(top, std::ceil(2.0 * v) / 2.0);
  cv::Mat img(size, size, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto at = [&](double x, double y) {
    return cv::Point(margin + static_cast<int>(std::clamp(x / top, 0.0, 1.0) * side),
                     size - margin - static_cast<int>(std::clamp(y / top, 0.0, 1.0) * side));
  };
  cv::rectangle(img, at(0, 0), at(top, top), kBlack);
  cv::line(img, at(0, 0), at(top, top), kGrey);
  for (double t = 0.0; t <= top + 1e-9; t += 0.5) {
    cv::putText(img, fixed(t, 1), at(t, 0) + cv::Point(-10, 20), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                kBlack);
    cv::putText(img, fixed(t, 1), at(0, t) + cv::Point(-35, 4), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                kBlack);
  }
  cv::putText(img, "min over fingers", cv::Point(size / 2 - 60, size - 15),
              cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack);
  cv::putText(img, "max over fingers; o open |Lk|, x VLk; green verified", cv::Point(10, 25),
              cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack);
  for (const auto& r : records) {
    const cv::Scalar colour = r.verified ? kGreen : kRed;
    if (std::isfinite(r.min_open_linking))
      cv::circle(img, at(r.min_open_linking, r.max_open_linking), 4, colour, 1, cv::LINE_AA);
    if (std::isfinite(r.min_virtual_linking))
      cv::drawMarker(img, at(r.min_virtual_linking, r.max_virtual_linking), colour,
                     cv::MARKER_CROSS, 8);
  }
  return img;
}

// Seconds per case (planning with the clasp checks), one bar each in the records' order.
cv::Mat time_per_case(const std::vector<BenchRecord>& records) {
  const int height = 360, margin = 50;
  const int bar = std::clamp(900 / std::max<int>(1, static_cast<int>(records.size())), 2, 24);
  const int width = 2 * margin + bar * static_cast<int>(records.size());
  cv::Mat img(height, std::max(width, 420), CV_8UC3, cv::Scalar(255, 255, 255));
  double top = 1e-3;
  for (const auto& r : records) top = std::max(top, r.seconds);
  const int base = height - margin, span = height - 2 * margin;
  cv::line(img, cv::Point(margin, base), cv::Point(img.cols - margin, base), kBlack);
  for (std::size_t i = 0; i < records.size(); ++i) {
    const int h = static_cast<int>(records[i].seconds / top * span);
    const int x = margin + static_cast<int>(i) * bar;
    cv::rectangle(img, cv::Point(x + 1, base - h), cv::Point(x + bar - 1, base),
                  records[i].verified ? kGreen : kRed, cv::FILLED);
  }
  cv::putText(img, "seconds per case (max " + fixed(top, 2) + " s); green verified",
              cv::Point(10, 25), cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack);
  return img;
}

// The verified paths whose scene was rendered, against that scene (truth_check.hpp).
std::string truth_markdown(const std::vector<BenchRecord>& all) {
  std::vector<const BenchRecord*> checked, touching;
  for (const auto& r : all) {
    if (!r.truth_checked) continue;
    checked.push_back(&r);
    if (!r.truth_contact.empty()) touching.push_back(&r);
  }
  if (checked.empty()) return "";
  std::ostringstream md;
  md << "\nAgainst the scene the depth was rendered from (the true mesh, boxes and clutter; no "
        "robot point more than 1 mm between checks, the fingers' closing left out): "
     << touching.size() << " of " << checked.size() << " verified paths touch it.\n";
  for (const BenchRecord* r : touching)
    md << "- " << r->name << (r->method.empty() ? "" : " (" + r->method + ")") << " seed "
       << r->seed << ": " << r->truth_contact << "\n";
  return md.str();
}

std::string report_markdown(const std::vector<BenchRecord>& all, const std::string& title) {
  const std::vector<BenchRecord> records = main_runs(all);
  struct Row {
    int cases = 0, success = 0, verified = 0;
    std::vector<double> seconds, counts;
    std::map<std::string, int> reasons;
  };
  std::map<std::string, Row> rows;
  for (const auto& r : records) {
    Row& row = rows[r.name];
    ++row.cases;
    row.success += r.success;
    row.verified += r.verified;
    if (r.achieved()) {
      row.seconds.push_back(r.seconds);
      row.counts.push_back(r.controller_only ? r.steps : r.cycles);
    } else {
      // The reason up to its first colon: "no clasp found within the time limit (10 s)".
      ++row.reasons[r.reason.substr(0, r.reason.find(':'))];
    }
  }
  const nlohmann::json s = bench_summary(records);
  std::ostringstream md;
  md << "# " << title << "\n\n"
     << s["verified"].get<int>() << " of " << s["cases"].get<int>()
     << " runs planned a verified clasp (" << s["success"].get<int>()
     << " succeeded: a clasp found, or with --controller-only the goal reached); median "
     << fixed(number_from(s, "median_seconds"), 2) << " s, max "
     << fixed(number_from(s, "max_seconds"), 2)
     << " s (planning with the clasp checks, perception excluded, runs that reached their aim).\n\n"
     << "| scenario | success | verified | median s | spread s | median cycles (steps with "
        "--controller-only) | other runs: main reason |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const auto& [name, row] : rows) {
    std::string spread = "-";
    if (!row.seconds.empty()) {
      const auto [lo, hi] = std::minmax_element(row.seconds.begin(), row.seconds.end());
      spread = fixed(*lo, 2) + "–" + fixed(*hi, 2);
    }
    std::string reason = "-";
    int most = 0;
    for (const auto& [text, count] : row.reasons)
      if (count > most) most = count, reason = text + " (" + std::to_string(count) + ")";
    md << "| " << name << " | " << row.success << "/" << row.cases << " | " << row.verified << "/"
       << row.cases << " | " << fixed(median(row.seconds), 2) << " | " << spread << " | "
       << fixed(median(row.counts), 0) << " | " << reason << " |\n";
  }
  md << truth_markdown(all);
  md << "\nFiles: cases.csv (one row per run), cases.json (read by `claspplan bench --merge`), "
        "linking_scatter.png (paper Fig. 6), time_per_case.png.\n";
  const auto sweep = sweep_runs(all);
  if (!sweep.empty()) md << sweep_markdown(sweep);
  for (const auto& method : methods(all))
    md << method_markdown(records, method_runs(all, method), method);
  return md.str();
}

}  // namespace

BenchRecord::BenchRecord()
    : min_open_linking(kNaN),
      max_open_linking(kNaN),
      min_virtual_linking(kNaN),
      max_virtual_linking(kNaN),
      final_linking(kNaN) {}

nlohmann::json record_json(const BenchRecord& r) {
  return {{"name", r.name},
          {"scenario", r.scenario},
          {"seed", r.seed},
          {"tolerance", r.tolerance},
          {"method", r.method},
          {"exit_code", r.exit_code},
          {"success", r.success},
          {"verified", r.verified},
          {"controller_only", r.controller_only},
          {"cycles", r.cycles},
          {"steps", r.steps},
          {"nodes", r.nodes},
          {"seconds", r.seconds},
          {"perception", r.perception},
          {"planning", r.planning},
          {"closing", r.closing},
          {"verification", r.verification},
          {"total", r.total},
          {"min_open_linking", number(r.min_open_linking)},
          {"max_open_linking", number(r.max_open_linking)},
          {"min_virtual_linking", number(r.min_virtual_linking)},
          {"max_virtual_linking", number(r.max_virtual_linking)},
          {"final_linking", number(r.final_linking)},
          {"reason", r.reason},
          {"truth_checked", r.truth_checked},
          {"truth_contact", r.truth_contact}};
}

BenchRecord record_from_json(const nlohmann::json& j) {
  BenchRecord r;
  try {
    r.name = j.at("name").get<std::string>();
    r.scenario = j.at("scenario").get<std::string>();
    r.seed = j.at("seed").get<std::uint64_t>();
    r.tolerance = j.at("tolerance").get<double>();
    r.method = j.at("method").get<std::string>();
    r.exit_code = j.at("exit_code").get<int>();
    r.success = j.at("success").get<bool>();
    r.verified = j.at("verified").get<bool>();
    r.controller_only = j.at("controller_only").get<bool>();
    r.cycles = j.at("cycles").get<int>();
    r.steps = j.at("steps").get<int>();
    r.nodes = j.at("nodes").get<int>();
    r.seconds = j.at("seconds").get<double>();
    r.perception = j.at("perception").get<double>();
    r.planning = j.at("planning").get<double>();
    r.closing = j.at("closing").get<double>();
    r.verification = j.at("verification").get<double>();
    r.total = j.at("total").get<double>();
    r.min_open_linking = number_from(j, "min_open_linking");
    r.max_open_linking = number_from(j, "max_open_linking");
    r.min_virtual_linking = number_from(j, "min_virtual_linking");
    r.max_virtual_linking = number_from(j, "max_virtual_linking");
    r.final_linking = number_from(j, "final_linking");
    r.reason = j.at("reason").get<std::string>();
    r.truth_checked = j.value("truth_checked", false);  // not in the records of older versions
    r.truth_contact = j.value("truth_contact", std::string());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(std::string("bench case record: ") + e.what());
  }
  return r;
}

nlohmann::json bench_summary(const std::vector<BenchRecord>& records) {
  int success = 0, verified = 0;
  std::vector<double> seconds;
  const auto main = main_runs(records);
  for (const auto& r : main) {
    success += r.success;
    verified += r.verified;
    if (r.achieved()) seconds.push_back(r.seconds);
  }
  nlohmann::json summary = {
      {"cases", main.size()},
      {"success", success},
      {"verified", verified},
      {"median_seconds", number(median(seconds))},
      {"max_seconds",
       number(seconds.empty() ? kNaN : *std::max_element(seconds.begin(), seconds.end()))}};
  for (const auto& method : bench_baselines()) {  // every baseline's key, with 0 cases if not run
    const auto runs = method_runs(records, method);
    int m_success = 0, m_verified = 0;
    std::vector<double> m_seconds;
    for (const auto& r : runs) {
      m_success += r.success;
      m_verified += r.verified;
      if (r.verified) m_seconds.push_back(r.seconds);
    }
    summary[method] = {{"cases", runs.size()},
                       {"success", m_success},
                       {"verified", m_verified},
                       {"median_seconds", number(median(m_seconds))}};
  }
  return summary;
}

void write_bench_report(const std::vector<BenchRecord>& records, const std::string& out_dir,
                        const std::string& title) {
  namespace fs = std::filesystem;
  const fs::path dir(out_dir);
  fs::create_directories(dir);
  nlohmann::json all = nlohmann::json::array();
  std::ostringstream csv;
  csv << "name,scenario,seed,tolerance,method,exit_code,success,verified,controller_only,cycles,"
         "steps,"
         "nodes,seconds,"
         "perception,planning,"
         "closing,verification,total,min_open_linking,max_open_linking,min_virtual_linking,"
         "max_virtual_linking,final_linking,reason,truth_checked,truth_contact\n";
  for (const auto& r : records) {
    all.push_back(record_json(r));
    csv << csv_text(r.name) << ',' << csv_text(r.scenario) << ',' << r.seed << ','
        << fixed(r.tolerance, 2) << ',' << csv_text(r.method) << ',' << r.exit_code << ','
        << r.success << ',' << r.verified << ',' << r.controller_only << ',' << r.cycles << ','
        << r.steps << ',' << r.nodes << ',' << fixed(r.seconds, 4) << ',' << fixed(r.perception, 4)
        << ',' << fixed(r.planning, 4) << ',' << fixed(r.closing, 4) << ','
        << fixed(r.verification, 4) << ',' << fixed(r.total, 4) << ','
        << fixed(r.min_open_linking, 4) << ',' << fixed(r.max_open_linking, 4) << ','
        << fixed(r.min_virtual_linking, 4) << ',' << fixed(r.max_virtual_linking, 4) << ','
        << fixed(r.final_linking, 4) << ',' << csv_text(r.reason) << ',' << r.truth_checked << ','
        << csv_text(r.truth_contact) << '\n';
  }
  write_text(dir / "cases.json", all.dump(2) + "\n");
  write_text(dir / "cases.csv", csv.str());
  write_text(dir / "report.md", report_markdown(records, title));
  write_png(dir / "linking_scatter.png", linking_scatter(main_runs(records)));
  write_png(dir / "time_per_case.png", time_per_case(main_runs(records)));
  const auto sweep = sweep_runs(records);
  if (!sweep.empty()) write_png(dir / "tolerance_sweep.png", tolerance_sweep(sweep));
  for (const auto& method : methods(records)) {
    write_png(dir / (method + "_time.png"),
              method_time(main_runs(records), method_runs(records, method), method));
  }
}

std::vector<BenchRecord> read_bench_cases(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw InputError(path + ": cannot read (not a bench output folder?)");
  nlohmann::json j;
  try {
    f >> j;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path + ": not JSON (" + std::string(e.what()) + ")");
  }
  if (!j.is_array()) throw InputError(path + ": expected an array of case records");
  std::vector<BenchRecord> records;
  for (const auto& item : j) {
    try {
      records.push_back(record_from_json(item));
    } catch (const std::invalid_argument& e) {
      throw InputError(path + ": " + e.what());
    }
  }
  return records;
}

}  // namespace claspplan::cli
