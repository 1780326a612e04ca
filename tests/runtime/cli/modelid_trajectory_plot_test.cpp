// The SVG of check-trajectory --plot (and design --plot, the same writer) read back: well-formed
// XML by a minimal parser of the test's own, one polyline per joint and key whose plotted
// extremes equal the series' extremes computed here on a fine grid; and the committed plot of
// the bundled TX-40 design (robots/data/tx40/design.svg) still is that design's.

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::test {
namespace {

namespace fs = std::filesystem;

struct Element {
  std::string name;
  std::map<std::string, std::string> attributes;
};

// The elements of an XML text in document order; a failure for anything not well-formed
// (unbalanced or crossed tags, unquoted or repeated attributes, '<' or a bare '&' where they
// cannot be, text after the root).
std::vector<Element> parse_xml(const std::string& text) {
  std::vector<Element> elements;
  std::vector<std::string> open;
  bool root_closed = false;
  std::size_t i = 0;
  const auto fail = [&](const std::string& why) {
    ADD_FAILURE() << "not well-formed at offset " << i << ": " << why;
    return std::vector<Element>{};
  };
  const auto check_entities = [&](const std::string& chunk) {
    for (std::size_t at = chunk.find('&'); at != std::string::npos; at = chunk.find('&', at + 1)) {
      const std::size_t end = chunk.find(';', at);
      const std::string entity = end == std::string::npos ? "" : chunk.substr(at, end - at + 1);
      if (entity != "&amp;" && entity != "&lt;" && entity != "&gt;" && entity != "&quot;" &&
          entity != "&apos;") {
        return false;
      }
    }
    return true;
  };
  while (i < text.size()) {
    if (text[i] != '<') {
      const std::size_t next = text.find('<', i);
      const std::string chunk = text.substr(i, next - i);
      if (!check_entities(chunk)) return fail("bare '&' in text");
      if ((open.empty()) && chunk.find_first_not_of(" \n\t\r") != std::string::npos) {
        return fail("text outside the root element");
      }
      if (next == std::string::npos) break;
      i = next;
      continue;
    }
    if (text.compare(i, 5, "<?xml") == 0) {
      if (i != 0) return fail("XML declaration not at the start");
      i = text.find("?>", i);
      if (i == std::string::npos) return fail("unterminated declaration");
      i += 2;
      continue;
    }
    const std::size_t end = text.find('>', i);
    if (end == std::string::npos) return fail("unterminated tag");
    std::string tag = text.substr(i + 1, end - i - 1);
    i = end + 1;
    if (!tag.empty() && tag[0] == '/') {
      if (open.empty() || open.back() != tag.substr(1)) return fail("unbalanced </" + tag.substr(1) + ">");
      open.pop_back();
      root_closed = open.empty();
      continue;
    }
    if (root_closed) return fail("a second root element");
    const bool empty = !tag.empty() && tag.back() == '/';
    if (empty) tag.pop_back();
    Element element;
    std::size_t k = 0;
    while (k < tag.size() && !std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
    element.name = tag.substr(0, k);
    if (element.name.empty()) return fail("empty tag name");
    while (true) {
      while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
      if (k == tag.size()) break;
      const std::size_t equals = tag.find('=', k);
      if (equals == std::string::npos || equals + 1 >= tag.size() || tag[equals + 1] != '"') {
        return fail("attribute without a quoted value in <" + element.name + ">");
      }
      const std::size_t close = tag.find('"', equals + 2);
      if (close == std::string::npos) return fail("unterminated attribute value");
      const std::string name = tag.substr(k, equals - k), value = tag.substr(equals + 2, close - equals - 2);
      if (value.find('<') != std::string::npos || !check_entities(value)) return fail("bad attribute value");
      if (!element.attributes.emplace(name, value).second) return fail("attribute " + name + " twice");
      k = close + 1;
    }
    elements.push_back(element);
    if (!empty) open.push_back(element.name);
    else root_closed = open.empty();
  }
  if (!open.empty()) return fail("<" + open.back() + "> never closed");
  return elements;
}

// The plotted values of one polyline: its pixel points through its data-axes map
// (x = X0 + SX t, y = YZ - SY value); `resolution` receives the value of 0.001 px.
std::vector<double> plotted_values(const Element& polyline, double& resolution) {
  std::istringstream axes(polyline.attributes.at("data-axes"));
  double x0, sx, yz, sy;
  axes >> x0 >> sx >> yz >> sy;
  resolution = 0.001 / sy;
  std::vector<double> values;
  std::istringstream points(polyline.attributes.at("points"));
  for (std::string point; points >> point;) {
    const std::size_t comma = point.find(',');
    values.push_back((yz - std::stod(point.substr(comma + 1))) / sy);
  }
  return values;
}

// A position-form series (Swevers 2002 eq. 15): per joint q0 and (harmonic, a, b) terms.
struct Series {
  double period = 0;
  std::vector<double> q0;
  std::vector<std::vector<std::array<double, 3>>> terms;

  // min q, max q, max |dq|, max |ddq| of joint j over `points` instants of one period.
  std::array<double, 4> extremes(std::size_t j, int points) const {
    const double wf = 2 * std::numbers::pi / period;
    std::array<double, 4> e{INFINITY, -INFINITY, 0, 0};
    for (int k = 0; k < points; ++k) {
      const double t = period * k / points;
      double q = q0[j], dq = 0, ddq = 0;
      for (const auto& [l, a, b] : terms[j]) {
        const double w = l * wf, s = std::sin(w * t), c = std::cos(w * t);
        q += a * s + b * c, dq += w * (a * c - b * s), ddq -= w * w * (a * s + b * c);
      }
      e[0] = std::min(e[0], q), e[1] = std::max(e[1], q);
      e[2] = std::max(e[2], std::abs(dq)), e[3] = std::max(e[3], std::abs(ddq));
    }
    return e;
  }
};

// Every polyline of `svg` against `series`: one per joint and key, its extremes those of the
// series to the plot's resolution.
void expect_plotted_extremes(const std::string& svg, const Series& series) {
  const std::vector<Element> elements = parse_xml(svg);
  ASSERT_FALSE(elements.empty());
  EXPECT_EQ(elements.front().name, "svg");
  int curves = 0;
  for (const Element& element : elements) {
    if (element.name != "polyline") continue;
    ++curves;
    const std::string key = element.attributes.at("class");
    const auto j = static_cast<std::size_t>(std::stoi(element.attributes.at("data-joint")) - 1);
    ASSERT_LT(j, series.q0.size());
    double resolution = 0;
    const std::vector<double> values = plotted_values(element, resolution);
    const std::array<double, 4> truth = series.extremes(j, 200000);
    const auto [low, high] = std::minmax_element(values.begin(), values.end());
    // The plot's rounding (0.001 px) and the dense grid's miss (5e-6 of a peak, limit_use.hpp).
    const double tolerance = resolution + 1e-5 * std::max({std::abs(truth[0]), std::abs(truth[1]), truth[2], truth[3]});
    const std::string what = "joint " + std::to_string(j + 1) + " " + key;
    if (key == "q") {
      EXPECT_NEAR(*low, truth[0], tolerance) << what;
      EXPECT_NEAR(*high, truth[1], tolerance) << what;
    } else {
      const double peak = std::max(std::abs(*low), std::abs(*high));
      EXPECT_NEAR(peak, key == "dq" ? truth[2] : truth[3], tolerance) << what;
    }
  }
  EXPECT_EQ(curves, static_cast<int>(3 * series.q0.size()));
}

TEST(ModelidTrajectoryPlot, IsWellFormedAndPlotsTheExtremes) {
  const fs::path dir = test_folder();
  write_text(dir / "two.yaml",
             "period: 2\nform: position\njoints:\n"
             "  - {q0: 0.1, terms: [{l: 1, a: 0.3, b: 0.2}, {l: 4, a: 0.05, b: -0.04}]}\n"
             "  - {q0: -0.2, terms: [{l: 1, a: -0.2, b: 0.1}, {l: 5, a: 0.01, b: 0.015}]}\n");
  const CliRun run = modelid("check-trajectory --robot " +
                             quoted_source("tests/bad_inputs/robots/two_axes_limited.yaml") +
                             " --trajectory " + quoted(dir / "two.yaml") + " --plot " +
                             quoted(dir / "plot"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("plot written to"), std::string::npos) << run.err;
  // Harmonics 4 and 5: between the plot's 400 equally spaced instants their peaks would be
  // missed by up to 5e-4 and 8e-4 of their size, several times the tolerance, had the plot
  // not added the instants of the extremes.
  Series series{2, {0.1, -0.2}, {{{1, 0.3, 0.2}, {4, 0.05, -0.04}}, {{1, -0.2, 0.1}, {5, 0.01, 0.015}}}};
  const std::string svg = read_text(dir / "plot" / "trajectory.svg");
  expect_plotted_extremes(svg, series);
  // Every limit of two_axes_limited.yaml drawn: two lines per joint and key.
  int limits = 0;
  for (const Element& element : parse_xml(svg)) {
    const auto found = element.attributes.find("class");
    limits += element.name == "line" && found != element.attributes.end() && found->second == "limit";
  }
  EXPECT_EQ(limits, 12);
}

TEST(ModelidTrajectoryPlot, CommittedTx40PlotIsTheBundledDesigns) {
  const YAML::Node root = YAML::LoadFile(source_path("robots/data/tx40/design.yaml"));
  Series series;
  series.period = root["period"].as<double>();
  for (const YAML::Node& joint : root["joints"]) {
    series.q0.push_back(joint["q0"].as<double>());
    const auto a = joint["a"].as<std::vector<double>>(), b = joint["b"].as<std::vector<double>>();
    series.terms.emplace_back();
    for (std::size_t l = 0; l < a.size(); ++l) {
      series.terms.back().push_back({static_cast<double>(l + 1), a[l], b[l]});
    }
  }
  expect_plotted_extremes(read_text(source_path("robots/data/tx40/design.svg")), series);
}

TEST(ModelidTrajectoryPlot, AnUnwritablePlotFolderFailsBeforeAnything) {
  const fs::path dir = test_folder();
  write_text(dir / "file", "");
  const CliRun run = modelid("check-trajectory --robot " +
                             quoted_source("tests/bad_inputs/robots/two_axes_limited.yaml") +
                             " --trajectory " + quoted_source("tests/bad_inputs/limits/beyond_velocity.yaml") +
                             " --plot " + quoted(dir / "file" / "plot"));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("error"), std::string::npos) << run.err;
  EXPECT_EQ(run.out, "");
}

}  // namespace
}  // namespace modelgen::test
