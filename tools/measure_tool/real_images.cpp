#include "measure_tool/real_images.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "common/input_error.h"
#include "common/units.h"
#include "sensing/door_classifier.h"
#include "sensing/sensing_geometry.h"

namespace stickrep::measure {
namespace {

constexpr int kFrameWidth = 512;
constexpr int kFrameHeight = 480;

std::string BaseName(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string Trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const std::size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

// One annotation line's columns: pairs of numbers, or "-".
std::vector<std::pair<double, double>> ParseColumns(const std::string& path, int line,
                                                    const std::string& name,
                                                    const std::string& text) {
  std::vector<std::pair<double, double>> doors;
  if (text == "-") return doors;
  std::istringstream in(text);
  std::vector<double> cols;
  std::string token;
  while (in >> token) {
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0' || !std::isfinite(v) || v < 0.0) {
      throw InputError(path, line, name, "'" + token + "' is not a column (a number >= 0)");
    }
    cols.push_back(v);
  }
  if (cols.empty() || cols.size() % 2 != 0) {
    throw InputError(path, line, name,
                     "needs pairs of jamb columns 'LJ RJ ...' or '-' for no door");
  }
  for (std::size_t k = 0; k < cols.size(); k += 2) {
    if (!(cols[k] < cols[k + 1])) {
      throw InputError(path, line, name, "left jamb must be left of the right jamb");
    }
    doors.push_back({cols[k], cols[k + 1]});
  }
  return doors;
}

struct Scored {
  int pairs = 0;
  int top_hit = -1;  // rank of the first pair on a true door among the first three, or -1
};

Scored Score(const std::vector<sensing::JambCandidate>& ranked,
             const std::vector<std::pair<double, double>>& truth, double tol) {
  Scored s;
  s.pairs = static_cast<int>(ranked.size());
  for (std::size_t k = 0; k < ranked.size() && k < 3 && s.top_hit < 0; ++k) {
    for (const auto& [l, r] : truth) {
      if (std::abs(ranked[k].footprints.lj_px - l) <= tol &&
          std::abs(ranked[k].footprints.rj_px - r) <= tol) {
        s.top_hit = static_cast<int>(k);
      }
    }
  }
  return s;
}

std::string Fmt(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), fmt, a, b, c, d);
  return buf;
}

// Candidates in the classifier's order (highest confidence first).
std::vector<sensing::JambCandidate> Ranked(const vision::RibbonDetection& det) {
  std::vector<sensing::JambCandidate> c = landmark::CandidatesAfterCasingRule(det, {});
  std::stable_sort(c.begin(), c.end(), [](const auto& a, const auto& b) {
    return a.confidence > b.confidence;
  });
  return c;
}

}  // namespace

std::map<std::string, std::vector<std::pair<double, double>>> LoadAnnotations(
    const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open the annotation file");
  std::map<std::string, std::vector<std::pair<double, double>>> out;
  std::string raw;
  for (int line = 1; std::getline(in, raw); ++line) {
    const std::string text = Trim(raw.substr(0, raw.find('#')));
    if (text.empty()) continue;
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos || Trim(text.substr(0, colon)).empty()) {
      throw InputError(path, line, "", "expected 'NAME: LJ RJ ...' or 'NAME: -'");
    }
    const std::string name = Trim(text.substr(0, colon));
    if (out.count(name)) throw InputError(path, line, name, "annotated twice");
    out[name] = ParseColumns(path, line, name, Trim(text.substr(colon + 1)));
  }
  return out;
}

cv::Mat LoadFrame(const std::string& path, int* source_width) {
  const cv::Mat grey = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (grey.empty()) throw InputError(path, 0, "", "cannot be read as an image (PNG, JPEG, ...)");
  if (source_width) *source_width = grey.cols;
  cv::Mat frame;
  cv::resize(grey, frame, cv::Size(kFrameWidth, kFrameHeight), 0, 0, cv::INTER_AREA);
  return frame;
}

cv::Mat DrawDetections(const cv::Mat& image, const vision::RibbonDetection& det,
                       const std::vector<sensing::JambCandidate>& ranked,
                       const std::vector<std::pair<double, double>>& truth,
                       const std::string& caption) {
  cv::Mat out;
  cv::cvtColor(image, out, cv::COLOR_GRAY2BGR);
  for (int r : det.rows) cv::line(out, {0, r}, {out.cols - 1, r}, {200, 120, 0}, 1);
  const int top = det.rows.empty() ? 0 : det.rows.front();
  const int bottom = det.rows.empty() ? out.rows - 1 : det.rows.back();
  for (const vision::Footprint& f : det.footprints) {
    const int c = static_cast<int>(std::lround(f.column_px));
    cv::line(out, {c, top - 12}, {c, top - 2}, {0, 220, 255}, 1);
  }
  const cv::Scalar colours[] = {{0, 200, 0}, {0, 140, 255}, {0, 0, 230}};
  for (int k = std::min<int>(3, static_cast<int>(ranked.size())) - 1; k >= 0; --k) {
    const int l = static_cast<int>(std::lround(ranked[k].footprints.lj_px));
    const int r = static_cast<int>(std::lround(ranked[k].footprints.rj_px));
    const int inset = 6 * k;
    cv::rectangle(out, {l, top + inset}, {r, bottom - inset}, colours[k], k == 0 ? 2 : 1);
  }
  for (const auto& [l, r] : truth) {
    for (double c : {l, r}) {
      const int x = static_cast<int>(std::lround(c));
      cv::line(out, {x, out.rows - 14}, {x, out.rows - 1}, {255, 0, 255}, 2);
    }
  }
  cv::putText(out, caption, {6, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 3);
  cv::putText(out, caption, {6, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {255, 255, 255}, 1);
  return out;
}

namespace {

// The annotated frames' tally.
struct ImageTally {
  long annotated = 0, with_pairs = 0, top_hits = 0;
  long door_frames = 0, door_top = 0, door_top3 = 0, empty_frames = 0, empty_with_pairs = 0;

  // Adds one annotated frame; returns its verdict line.
  std::string Add(const Scored& sc, bool door_free) {
    ++annotated;
    with_pairs += sc.pairs > 0;
    top_hits += sc.top_hit == 0;
    if (door_free) {
      ++empty_frames;
      empty_with_pairs += sc.pairs > 0;
      return sc.pairs > 0 ? "  annotated: no door (pairs offered)\n" : "  annotated: no door\n";
    }
    ++door_frames;
    door_top += sc.top_hit == 0;
    door_top3 += sc.top_hit >= 0;
    return sc.top_hit < 0 ? std::string("  annotated door: not among the first three\n")
                          : Fmt("  annotated door: pair %.0f\n", sc.top_hit);
  }

  std::string Summary() const {
    if (annotated == 0) return "";
    const auto pct = [](long a, long b) { return b > 0 ? 100.0 * a / b : 0.0; };
    std::string s = Fmt(
        "annotated frames %.0f: precision of the first pair %.1f %% (%.0f of %.0f with pairs)\n",
        annotated, pct(top_hits, with_pairs), top_hits, with_pairs);
    s += Fmt("  recall: first pair %.1f %%, first three %.1f %% of %.0f door frames\n",
             pct(door_top, door_frames), pct(door_top3, door_frames), door_frames);
    s += Fmt("  door-free frames with pairs: %.0f of %.0f\n", empty_with_pairs, empty_frames);
    return s;
  }
};

// The width gate without a sonar: the configured range and stares, every legal class.
vision::PairWidthLimits GateWithoutSonar(const ImageRunConfig& config,
                                         const sensing::RobotConfig& robot) {
  landmark::WidthGate gate;
  gate.stare_tolerance_deg = config.max_stare_deg;
  gate.range_tolerance = config.range_tolerance;
  double max_class = 0.0, min_class = 1e9;
  for (const sensing::ClassBoundary& b : sensing::DefaultBoundaries()) {
    min_class = std::min(min_class, b.low_in);
    max_class = std::max(max_class, b.high_in);
  }
  return landmark::LegalPairWidths(sensing::CameraModel::FromConfig(robot.camera),
                                   config.range_in, 0.0, min_class,
                                   max_class + 2.0 * gate.casing_allowance_in, gate);
}

// The frame's detection and its first `top` candidates.
std::string DescribeFrame(const std::string& path, const vision::RibbonDetection& det,
                          const std::vector<sensing::JambCandidate>& ranked, int top) {
  std::string s = path + Fmt(": threshold %.1f, %.0f footprints, %.0f pairs", det.threshold,
                             det.footprints.size(), ranked.size());
  s += det.ground >= 0.0 ? Fmt(", wall level %.0f\n", det.ground) : "\n";
  for (int k = 0; k < top && k < static_cast<int>(ranked.size()); ++k) {
    const sensing::JambCandidate& c = ranked[k];
    s += Fmt("  %.0f  LJ %7.1f  RJ %7.1f  width %6.1f px", k, c.footprints.lj_px,
             c.footprints.rj_px, c.footprints.rj_px - c.footprints.lj_px);
    s += Fmt("  confidence %.3f\n", c.confidence);
  }
  return s;
}

}  // namespace

std::string RunOnImages(const ImageRunConfig& config, const sensing::RobotConfig& robot) {
  std::map<std::string, std::vector<std::pair<double, double>>> truth;
  if (!config.annotations.empty()) truth = LoadAnnotations(config.annotations);
  const vision::RibbonDetector detector;
  const vision::PairWidthLimits limits = GateWithoutSonar(config, robot);
  std::string s = Fmt("range %.0f in; stares within %.0f deg; pair widths %.1f..%.1f px\n",
                      config.range_in, config.max_stare_deg, limits.min_px, limits.max_px);
  ImageTally tally;
  for (const std::string& path : config.files) {
    int source_width = kFrameWidth;
    const cv::Mat frame = LoadFrame(path, &source_width);
    const vision::DetectResult r = detector.Detect(frame, config.range_in, limits);
    const std::vector<sensing::JambCandidate> ranked = Ranked(r.detection);
    s += DescribeFrame(path, r.detection, ranked, config.top);
    std::vector<std::pair<double, double>> doors;
    const auto t = truth.find(BaseName(path));
    if (t != truth.end()) {
      const double scale = static_cast<double>(kFrameWidth) / source_width;
      for (const auto& [l, rr] : t->second) doors.push_back({l * scale, rr * scale});
      s += tally.Add(Score(ranked, doors, config.hit_tolerance_px), doors.empty());
    }
    if (!config.draw_dir.empty()) {
      const std::string out = config.draw_dir + "/" + BaseName(path) + ".png";
      if (!cv::imwrite(out, DrawDetections(frame, r.detection, ranked, doors, BaseName(path)))) {
        throw InputError(out, 0, "", "cannot write the drawn frame");
      }
    }
  }
  return s + tally.Summary();
}

}  // namespace stickrep::measure
