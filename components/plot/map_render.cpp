#include "plot/map_render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace stickrep::map {

namespace {

// BGR colours per door class (30, 32, 36, 40, 30/30, 36/36), chosen to stay apart in print.
const cv::Scalar kDoorColours[kDoorClassCount] = {{0, 140, 255}, {0, 200, 0},   {200, 60, 0},
                                                  {0, 0, 220},   {180, 0, 180}, {120, 120, 0}};
const cv::Scalar kWallColour(60, 60, 60);
const cv::Scalar kOtherColour(200, 0, 255);
const cv::Scalar kJoinColour(150, 150, 150);

// A pose at pixel p: a dot, a 32 px arrow along the heading (image rows grow downwards) and
// the label right of the dot, or left of it where the image ends.
void DrawPose(cv::Mat& img, const cv::Point& p, const PoseOverlay& pose) {
  const cv::Point tip(p.x + static_cast<int>(std::lround(32.0 * std::cos(pose.heading_rad))),
                      p.y - static_cast<int>(std::lround(32.0 * std::sin(pose.heading_rad))));
  cv::circle(img, p, 6, cv::Scalar(0, 0, 0), cv::FILLED, cv::LINE_AA);
  cv::arrowedLine(img, p, tip, cv::Scalar(0, 0, 0), 3, cv::LINE_AA, 0, 0.35);
  const int label_px = cv::getTextSize(pose.label, cv::FONT_HERSHEY_SIMPLEX, 0.5, 1, nullptr).width;
  const int label_x = p.x + 10 + label_px < img.cols ? p.x + 10 : p.x - 10 - label_px;
  cv::putText(img, pose.label, {label_x, p.y - 10}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

constexpr int kMarginPx = 40, kLegendPx = 70;

// Building inches to image pixels: the map's bounding box fitted to the image width between
// margins, y upwards (image rows grow downwards), the legend strip below.
struct MapToImage {
  double min_x = 0.0, min_y = 0.0;
  double scale = 1.0;  // px per inch
  int height = 0;
  cv::Point At(double x_in, double y_in) const {
    return cv::Point(
        static_cast<int>(std::lround(kMarginPx + (x_in - min_x) * scale)),
        static_cast<int>(std::lround(height - kLegendPx - kMarginPx - (y_in - min_y) * scale)));
  }
  cv::Point At(const Node& n) const { return At(n.x_in, n.y_in); }
};

MapToImage FitMap(const Map& map, int width_px) {
  double min_x = std::numeric_limits<double>::max(), min_y = min_x;
  double max_x = std::numeric_limits<double>::lowest(), max_y = max_x;
  for (const Ring& ring : map.rings()) {
    for (const Node& n : ring.nodes) {
      min_x = std::min(min_x, n.x_in);
      max_x = std::max(max_x, n.x_in);
      min_y = std::min(min_y, n.y_in);
      max_y = std::max(max_y, n.y_in);
    }
  }
  const double span_x = std::max(1.0, max_x - min_x), span_y = std::max(1.0, max_y - min_y);
  MapToImage to_px;
  to_px.min_x = min_x;
  to_px.min_y = min_y;
  to_px.scale = (width_px - 2.0 * kMarginPx) / span_x;
  to_px.height =
      std::clamp(static_cast<int>(span_y * to_px.scale) + 2 * kMarginPx + kLegendPx, 200, 6000);
  return to_px;
}

// Joins first, so that the rings are drawn over them.
void DrawRings(cv::Mat& img, const Map& map, const MapToImage& to_px, bool label_rings) {
  for (const Join& j : map.joins()) {
    const Ring& a = map.ring(map.FindRing(j.ring));
    const Ring& b = map.ring(map.FindRing(j.to_ring));
    cv::line(img, to_px.At(a.nodes[j.node]), to_px.At(b.nodes[j.to_node]), kJoinColour, 1,
             cv::LINE_AA);
  }
  const int door_px = std::max(3, static_cast<int>(std::lround(6.0 * to_px.scale)));
  for (const Ring& ring : map.rings()) {
    for (int i = 0; i < ring.EdgeCount(); ++i) {
      const cv::Point a = to_px.At(ring.nodes[i]);
      const cv::Point b = to_px.At(ring.nodes[(i + 1) % ring.NodeCount()]);
      const Edge& e = ring.edges[i];
      if (e.IsDoor()) {
        cv::line(img, a, b, kDoorColours[static_cast<int>(*e.door_class)], door_px, cv::LINE_8);
      } else if (e.IsWall()) {
        cv::line(img, a, b, kWallColour, 1, cv::LINE_AA);
      } else {
        cv::line(img, a, b, kOtherColour, door_px, cv::LINE_8);
      }
    }
    for (const Node& n : ring.nodes) {
      if (n.artificial) cv::circle(img, to_px.At(n), 6, cv::Scalar(0, 0, 0), 2, cv::LINE_AA);
    }
    if (label_rings) {
      cv::putText(img, ring.id, to_px.At(ring.nodes[0]) + cv::Point(8, 16),
                  cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(40, 40, 40), 1, cv::LINE_AA);
    }
  }
}

// What is drawn over the map: obstacles, then paths, markers and poses in that order.
void DrawOverlays(cv::Mat& img, const Map& map, const MapToImage& to_px,
                  const RenderOptions& options) {
  // Obstacles (columns, piers): filled grey.
  for (const Obstacle& o : map.obstacles()) {
    std::vector<cv::Point> corners;
    for (const auto& c : o.polygon_in) corners.push_back(to_px.At(c[0], c[1]));
    cv::fillPoly(img, std::vector<std::vector<cv::Point>>{corners}, cv::Scalar(150, 150, 150),
                 cv::LINE_AA);
  }
  for (const PathOverlay& path_overlay : options.paths) {
    for (size_t i = 1; i < path_overlay.points_in.size(); ++i) {
      const auto& a = path_overlay.points_in[i - 1];
      const auto& b = path_overlay.points_in[i];
      cv::line(img, to_px.At(a.first, a.second), to_px.At(b.first, b.second), cv::Scalar(0, 0, 220),
               2, cv::LINE_AA);
    }
  }
  for (const MarkerOverlay& m : options.markers) {
    const cv::Point p = to_px.At(m.x_in, m.y_in);
    cv::circle(img, p, 7, cv::Scalar(0, 140, 0), cv::FILLED, cv::LINE_AA);
    cv::putText(img, m.label, {p.x + 10, p.y - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(0, 100, 0), 1, cv::LINE_AA);
  }
  for (const PoseOverlay& pose : options.poses) DrawPose(img, to_px.At(pose.x_in, pose.y_in), pose);
}

// Legend and scale bar, along the strip below the map.
void DrawLegend(cv::Mat& img, const MapToImage& to_px) {
  int x = kMarginPx;
  const int y = to_px.height - kLegendPx / 2;
  for (int k = 0; k < kDoorClassCount; ++k) {
    cv::line(img, {x, y}, {x + 30, y}, kDoorColours[k], 6);
    cv::putText(img, std::string("door ") + DoorClassName(static_cast<DoorClass>(k)),
                {x + 36, y + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(20, 20, 20), 1,
                cv::LINE_AA);
    x += 140;
  }
  cv::line(img, {x, y}, {x + 30, y}, kWallColour, 1);
  cv::putText(img, "wall", {x + 36, y + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(20, 20, 20),
              1, cv::LINE_AA);
  x += 100;
  cv::line(img, {x, y}, {x + 30, y}, kOtherColour, 6);
  cv::putText(img, "other type", {x + 36, y + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
              cv::Scalar(20, 20, 20), 1, cv::LINE_AA);
  x += 130;
  cv::circle(img, {x + 6, y}, 6, cv::Scalar(0, 0, 0), 2, cv::LINE_AA);
  cv::putText(img, "artificial node / join", {x + 18, y + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
              cv::Scalar(20, 20, 20), 1, cv::LINE_AA);
  x += 230;
  // A scale bar of a round number of feet.
  double bar_ft = 10;
  while (bar_ft * 12 * to_px.scale < 80) bar_ft *= 2;
  const int bar_px = static_cast<int>(bar_ft * 12 * to_px.scale);
  cv::line(img, {x, y}, {x + bar_px, y}, cv::Scalar(0, 0, 0), 2);
  cv::putText(img, cv::format("%.0f ft", bar_ft), {x + bar_px + 6, y + 5}, cv::FONT_HERSHEY_SIMPLEX,
              0.5, cv::Scalar(20, 20, 20), 1, cv::LINE_AA);
}

}  // namespace

void RenderMapPng(const Map& map, const std::string& path, const RenderOptions& options) {
  const MapToImage to_px = FitMap(map, options.width_px);
  cv::Mat img(to_px.height, options.width_px, CV_8UC3, cv::Scalar(255, 255, 255));
  DrawRings(img, map, to_px, options.label_rings);
  DrawOverlays(img, map, to_px, options);
  DrawLegend(img, to_px);
  cv::putText(img, map.info().name, {kMarginPx, 24}, cv::FONT_HERSHEY_SIMPLEX, 0.7,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  if (!cv::imwrite(path, img)) throw std::runtime_error("cannot write " + path);
}

}  // namespace stickrep::map
