#pragma once
// Helpers shared by the map editor's offscreen GUI and crash tests: clicks in world
// coordinates on the editor's tool layer, and a JSON comparison with a tolerance on numbers.

#include <gtest/gtest.h>

#include <QTest>
#include <nlohmann/json.hpp>
#include <string>

#include "widgets/canvas/map_canvas.hpp"
#include "widgets/editor/editor_layer.hpp"

namespace irgs::gui::test {

inline QPoint toPixel(const widgets::MapCanvas& canvas, double x, double y) {
  return canvas.worldToWidget(Vec2(x, y)).toPoint();
}

inline void clickAt(widgets::EditorLayer& layer, const widgets::MapCanvas& canvas, double x,
                    double y) {
  QTest::mouseClick(&layer, Qt::LeftButton, {}, toPixel(canvas, x, y));
}

inline void dragFromTo(widgets::EditorLayer& layer, const widgets::MapCanvas& canvas, Vec2 from,
                       Vec2 to) {
  QTest::mousePress(&layer, Qt::LeftButton, {}, toPixel(canvas, from.x(), from.y()));
  const Vec2 mid = (from + to) / 2.0;
  QTest::mouseMove(&layer, toPixel(canvas, mid.x(), mid.y()));
  QTest::mouseMove(&layer, toPixel(canvas, to.x(), to.y()));
  QTest::mouseRelease(&layer, Qt::LeftButton, {}, toPixel(canvas, to.x(), to.y()));
}

// Empty when equal (numbers within `tolerance`), otherwise the JSON pointer of the first
// difference.
inline std::string jsonDifference(const nlohmann::json& a, const nlohmann::json& b,
                                  double tolerance = 1e-9, const std::string& at = "") {
  if (a.is_number() && b.is_number())
    return std::abs(a.get<double>() - b.get<double>()) <= tolerance ? "" : at + " (number)";
  if (a.type() != b.type())
    return at + " (type)";
  if (a.is_object()) {
    if (a.size() != b.size())
      return at + " (keys)";
    for (auto it = a.begin(); it != a.end(); ++it) {
      if (!b.contains(it.key()))
        return at + "/" + it.key() + " (missing)";
      std::string d = jsonDifference(it.value(), b[it.key()], tolerance, at + "/" + it.key());
      if (!d.empty())
        return d;
    }
    return "";
  }
  if (a.is_array()) {
    if (a.size() != b.size())
      return at + " (length)";
    for (std::size_t i = 0; i < a.size(); ++i) {
      std::string d = jsonDifference(a[i], b[i], tolerance, at + "/" + std::to_string(i));
      if (!d.empty())
        return d;
    }
    return "";
  }
  return a == b ? "" : at + " (value)";
}

}  // namespace irgs::gui::test
