#include "widgets/console/console_widget.hpp"

#include <gtest/gtest.h>

#include <QApplication>
#include <QCheckBox>
#include <QClipboard>
#include <QLineEdit>
#include <QPlainTextEdit>

namespace irgs::widgets {
namespace {

class ConsoleWidgetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    console.appendEvent(ConsoleLevel::kInfo, 0.5, "Simulator started");
    console.appendEvent(ConsoleLevel::kSensor, 1.25, "Sonar 3: echo at 1.20 m");
    console.appendEvent(ConsoleLevel::kWarning, 2.0, "Bumper front pressed");
    console.appendEvent(ConsoleLevel::kError, 12.34, "Link lost: SONAR board silent");
  }
  QStringList visibleLines() const {
    const QString text = console.visibleText();
    return text.isEmpty() ? QStringList() : text.split('\n');
  }
  QString viewText() const {
    return console.findChild<QPlainTextEdit*>("consoleView")->toPlainText();
  }

  ConsoleWidget console;
};

TEST_F(ConsoleWidgetTest, FormatsTimestampAndLevel) {
  EXPECT_EQ(ConsoleWidget::formatLine(ConsoleLevel::kWarning, 12.34, "x"), "[  12.34 s] WARN   x");
  EXPECT_EQ(ConsoleWidget::formatLine(ConsoleLevel::kSensor, 0.0, "a\nb"),
            "[   0.00 s] SENSOR a b");
  EXPECT_EQ(visibleLines().size(), 4);
  EXPECT_EQ(console.lineCount(), 4);
}

TEST_F(ConsoleWidgetTest, FilterHidesNonMatchingLinesCaseInsensitively) {
  console.findChild<QLineEdit*>("consoleFilter")->setText("sonar");
  const QStringList lines = visibleLines();
  ASSERT_EQ(lines.size(), 2);
  EXPECT_TRUE(lines[0].contains("Sonar 3"));
  EXPECT_TRUE(lines[1].contains("SONAR board"));
  EXPECT_EQ(viewText(), console.visibleText());
  EXPECT_EQ(console.lineCount(), 4);  // hidden, not dropped

  console.setFilterText("");
  EXPECT_EQ(visibleLines().size(), 4);
  EXPECT_EQ(viewText(), console.visibleText());
}

TEST_F(ConsoleWidgetTest, NewLinesHonourTheFilter) {
  console.setFilterText("bumper");
  console.appendEvent(ConsoleLevel::kWarning, 3.0, "Bumper left pressed");
  console.appendEvent(ConsoleLevel::kInfo, 3.5, "Paused");
  const QStringList lines = visibleLines();
  ASSERT_EQ(lines.size(), 2);
  EXPECT_TRUE(lines[1].contains("Bumper left"));
}

TEST_F(ConsoleWidgetTest, LevelCheckBoxesHideLevels) {
  console.findChild<QCheckBox*>("consoleLevelSensor")->setChecked(false);
  console.findChild<QCheckBox*>("consoleLevelInfo")->setChecked(false);
  EXPECT_FALSE(console.levelVisible(ConsoleLevel::kSensor));
  const QStringList lines = visibleLines();
  ASSERT_EQ(lines.size(), 2);
  EXPECT_TRUE(lines[0].contains("WARN"));
  EXPECT_TRUE(lines[1].contains("ERROR"));
  EXPECT_EQ(viewText(), console.visibleText());
  console.setLevelVisible(ConsoleLevel::kInfo, true);
  EXPECT_TRUE(console.findChild<QCheckBox*>("consoleLevelInfo")->isChecked());
  EXPECT_EQ(visibleLines().size(), 3);
}

TEST_F(ConsoleWidgetTest, LineCountIsBounded) {
  console.setMaximumLines(100);
  for (int i = 0; i < 150; ++i)
    console.appendEvent(ConsoleLevel::kInfo, i, QString("line %1").arg(i));
  EXPECT_EQ(console.lineCount(), 100);
  const QStringList lines = visibleLines();
  ASSERT_EQ(lines.size(), 100);
  EXPECT_TRUE(lines.front().endsWith("line 50"));
  EXPECT_TRUE(lines.back().endsWith("line 149"));
}

TEST_F(ConsoleWidgetTest, DefaultBoundIsTwentyThousandLines) {
  for (int i = 0; i < ConsoleWidget::kDefaultMaximumLines + 10; ++i)
    console.appendEvent(ConsoleLevel::kSensor, i * 0.1, "tick");
  EXPECT_EQ(console.lineCount(), ConsoleWidget::kDefaultMaximumLines);
  console.setFilterText("tick");  // rebuilding the view from 20000 lines stays cheap
  EXPECT_EQ(visibleLines().size(), ConsoleWidget::kDefaultMaximumLines);
}

TEST_F(ConsoleWidgetTest, ClearRemovesEverything) {
  console.clear();
  EXPECT_EQ(console.lineCount(), 0);
  EXPECT_TRUE(console.visibleText().isEmpty());
  EXPECT_TRUE(viewText().isEmpty());
}

TEST_F(ConsoleWidgetTest, CopyTakesTheVisibleLinesWithoutSelection) {
  console.setFilterText("pressed");
  console.copyToClipboard();
  EXPECT_EQ(QApplication::clipboard()->text(), "[   2.00 s] WARN   Bumper front pressed");
}

}  // namespace
}  // namespace irgs::widgets
