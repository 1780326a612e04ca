// The SVG of a Fourier excitation against its limits; see trajectory_plot.hpp. Plain SVG 1.1
// text: frames, dashed limits, polylines in pixels (a transform from data coordinates would
// scale the strokes with the axes in renderers without vector-effect, librsvg among them).

#include "runtime/cli/plots/trajectory_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <sstream>

#include "modelgen/excitation/limit_use.hpp"
#include "runtime/cli/common/arguments.hpp"

namespace modelgen::internal {

namespace {

namespace fs = std::filesystem;

// Panel geometry, px.
constexpr double kPanelWidth = 260, kPanelHeight = 110, kLeft = 110, kTop = 60, kGapX = 60,
                 kGapY = 36;

std::string number(double value, int digits = 7) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

struct Curve {
  std::vector<double> t, value;
};

}  // namespace

std::string trajectory_svg(const FourierTrajectory& trajectory, const ModelSource& source,
                           const std::vector<JointLimits>& limits, const std::string& title,
                           int points) {
  const Eigen::Index dof = trajectory.q0.size();
  const double period = trajectory.period;
  // The instants: equally spaced, one period closed, and the extremes of the dense grid.
  std::vector<double> times;
  for (int k = 0; k <= points; ++k) times.push_back(period * k / points);
  const std::vector<JointExtremes> extremes = trajectory_extremes(trajectory);
  for (const JointExtremes& e : extremes) {
    for (double t : {e.q_min_time, e.q_max_time, e.dq_time, e.ddq_time}) times.push_back(t);
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  std::vector<Curve> curves(static_cast<std::size_t>(3 * dof));
  Eigen::VectorXd q, dq, ddq;
  for (double t : times) {
    trajectory.evaluate(t, q, dq, ddq);
    for (Eigen::Index j = 0; j < dof; ++j) {
      const double values[3] = {q[j], dq[j], ddq[j]};
      for (int key = 0; key < 3; ++key) {
        Curve& curve = curves[static_cast<std::size_t>(3 * j + key)];
        curve.t.push_back(t);
        curve.value.push_back(values[key]);
      }
    }
  }

  const double width = kLeft + 3 * kPanelWidth + 2 * kGapX + 30;
  const double height = kTop + static_cast<double>(dof) * (kPanelHeight + kGapY) + 10;
  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"10\" y=\"18\" font-size=\"13\">" << escaped(title) << "</text>\n"
      << "<text x=\"10\" y=\"34\" fill=\"#555\">one period of " << number(period) << " s; "
      << "dashed red: the limits, labelled on the left</text>\n";
  const char* headings[3] = {"q (rad or m)", "dq (per s)", "ddq (per s\u00b2)"};
  const char* classes[3] = {"q", "dq", "ddq"};
  for (int key = 0; key < 3; ++key) {
    svg << "<text x=\"" << kLeft + key * (kPanelWidth + kGapX) << "\" y=\"" << kTop - 8
        << "\" font-weight=\"bold\">" << headings[key] << "</text>\n";
  }
  for (Eigen::Index j = 0; j < dof; ++j) {
    const double y0 = kTop + static_cast<double>(j) * (kPanelHeight + kGapY);
    std::string name = std::to_string(j + 1);
    if (static_cast<std::size_t>(j) < source.joint_names.size()) {
      name += " " + source.joint_names[static_cast<std::size_t>(j)];
    }
    svg << "<text x=\"10\" y=\"" << y0 + kPanelHeight / 2 << "\" font-weight=\"bold\">"
        << escaped(name) << "</text>\n";
    const JointLimits limit =
        static_cast<std::size_t>(j) < limits.size() ? limits[static_cast<std::size_t>(j)] : JointLimits{};
    for (int key = 0; key < 3; ++key) {
      const Curve& curve = curves[static_cast<std::size_t>(3 * j + key)];
      // The limit lines of this panel, and a value range that shows them and the curve.
      std::vector<double> lines;
      if (key == 0 && limit.q_lower && limit.q_upper) lines = {*limit.q_lower, *limit.q_upper};
      if (key == 1 && limit.dq) lines = {-*limit.dq, *limit.dq};
      if (key == 2 && limit.ddq) lines = {-*limit.ddq, *limit.ddq};
      double low = *std::min_element(curve.value.begin(), curve.value.end());
      double high = *std::max_element(curve.value.begin(), curve.value.end());
      for (double line : lines) low = std::min(low, line), high = std::max(high, line);
      if (key > 0) high = std::max(high, -low), low = -high;  // symmetric about 0
      if (!(high > low)) low -= 1, high += 1;
      const double pad = 0.06 * (high - low);
      low -= pad, high += pad;
      const double x0 = kLeft + key * (kPanelWidth + kGapX);
      const double sx = kPanelWidth / period, sy = kPanelHeight / (high - low);
      const auto y_of = [&](double v) { return y0 + (high - v) * sy; };
      svg << "<g>\n<rect x=\"" << x0 << "\" y=\"" << y0 << "\" width=\"" << kPanelWidth
          << "\" height=\"" << kPanelHeight << "\" fill=\"none\" stroke=\"#999\"/>\n";
      if (low < 0 && high > 0) {
        svg << "<line x1=\"" << x0 << "\" y1=\"" << number(y_of(0)) << "\" x2=\"" << x0 + kPanelWidth
            << "\" y2=\"" << number(y_of(0)) << "\" stroke=\"#ddd\"/>\n";
      }
      for (double line : lines) {
        svg << "<line class=\"limit\" x1=\"" << x0 << "\" y1=\"" << number(y_of(line)) << "\" x2=\""
            << x0 + kPanelWidth << "\" y2=\"" << number(y_of(line))
            << "\" stroke=\"#d62728\" stroke-dasharray=\"5,3\"/>\n";
      }
      // Value labels at the left: the limits where there are some, else the range; the time
      // at the ends below.
      const std::vector<double> labelled = lines.empty() ? std::vector<double>{low, high} : lines;
      for (double v : labelled) {
        svg << "<text x=\"" << x0 - 4 << "\" y=\"" << number(y_of(v) + 4) << "\" text-anchor=\"end\" "
            << "fill=\"" << (lines.empty() ? "#555" : "#d62728") << "\">" << number(v, 3) << "</text>\n";
      }
      svg << "<text x=\"" << x0 << "\" y=\"" << y0 + kPanelHeight + 13 << "\" fill=\"#555\">0</text>\n<text x=\""
          << x0 + kPanelWidth << "\" y=\"" << y0 + kPanelHeight + 13
          << "\" text-anchor=\"end\" fill=\"#555\">" << number(period) << " s</text>\n";
      // The curve in pixels, x = x0 + sx t and y = yz - sy value, the map in data-axes.
      const double yz = y0 + high * sy;
      svg << "<polyline class=\"" << classes[key] << "\" data-joint=\"" << j + 1
          << "\" data-axes=\"" << number(x0, 17) << " " << number(sx, 17) << " " << number(yz, 17)
          << " " << number(sy, 17) << "\" fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"1.2\" points=\"";
      char point[64];
      for (std::size_t k = 0; k < curve.t.size(); ++k) {
        std::snprintf(point, sizeof point, "%s%.2f,%.3f", k ? " " : "", x0 + sx * curve.t[k],
                      yz - sy * curve.value[k]);
        svg << point;
      }
      svg << "\"/>\n</g>\n";
    }
  }
  svg << "</svg>\n";
  return svg.str();
}

std::string write_trajectory_plot(const std::string& dir, const FourierTrajectory& trajectory,
                                  const ModelSource& source, const std::vector<JointLimits>& limits,
                                  const std::string& title) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw std::runtime_error(dir + ": error: cannot create the plot folder: " + error.message());
  const std::string path = (fs::path(dir) / "trajectory.svg").string();
  write_file(path, trajectory_svg(trajectory, source, limits, title));
  return path;
}

}  // namespace modelgen::internal
