#include "widgets/link/signing_key_box.hpp"

#include <gtest/gtest.h>

#include <QCheckBox>
#include <QClipboard>
#include <QFile>
#include <QGuiApplication>
#include <QLabel>
#include <QPushButton>
#include <QRegularExpression>
#include <QSignalSpy>
#include <QTemporaryDir>

#include "widgets/link/connection_dialog.hpp"

namespace irgs::widgets {
namespace {

const QString kKeyA = QString(64, QLatin1Char('a'));
const QString kKeyB = QStringLiteral("0123456789abcdef").repeated(4);

// Stand-ins for the application's key rules: 64 hex digits, lower case; the fingerprint is a
// marked prefix; generate hands out kKeyB.
SigningKeyTools tools() {
  SigningKeyTools t;
  t.generate = [] { return kKeyB; };
  t.parse = [](const QString& text, QString* error) {
    static const QRegularExpression kHex(QStringLiteral("^[0-9a-fA-F]{64}$"));
    const QString key = text.trimmed();
    if (!kHex.match(key).hasMatch()) {
      *error = QStringLiteral("not 64 hex digits");
      return QString();
    }
    return key.toLower();
  };
  t.fingerprint = [](const QString& key) { return QStringLiteral("fp:") + key.left(4); };
  return t;
}

QCheckBox* switchOf(const SigningKeyBox& box) {
  return box.findChild<QCheckBox*>(QStringLiteral("linkSigning"));
}

TEST(SigningKeyBox, WithoutAKeySigningCannotBeSwitchedOn) {
  SigningKeyBox box(tools(), SigningChoice{true, {}});
  EXPECT_FALSE(switchOf(box)->isEnabled());
  EXPECT_EQ(box.choice(), (SigningChoice{false, {}}));
  EXPECT_EQ(box.fingerprintText(), QStringLiteral("none yet"));
  box.setSigningEnabled(true);
  EXPECT_FALSE(box.choice().enabled);
  EXPECT_FALSE(box.findChild<QPushButton*>(QStringLiteral("linkSigningExport"))->isEnabled());
}

TEST(SigningKeyBox, ASavedKeyShowsOnlyItsFingerprint) {
  SigningKeyBox box(tools(), SigningChoice{true, kKeyA.toUpper()});
  EXPECT_EQ(box.choice(), (SigningChoice{true, kKeyA}));
  EXPECT_TRUE(switchOf(box)->isChecked());
  EXPECT_EQ(box.fingerprintText(), QStringLiteral("fp:aaaa"));
  for (const QLabel* label : box.findChildren<QLabel*>())
    EXPECT_FALSE(label->text().contains(kKeyA)) << label->text().toStdString();
}

TEST(SigningKeyBox, ANewKeyReplacesTheOldAndCanBeSwitchedOn) {
  SigningKeyBox box(tools(), SigningChoice{false, kKeyA});
  QSignalSpy changed(&box, &SigningKeyBox::changed);
  box.findChild<QPushButton*>(QStringLiteral("linkSigningNewKey"))->click();
  EXPECT_EQ(box.choice().key, kKeyB);
  EXPECT_EQ(box.fingerprintText(), QStringLiteral("fp:0123"));
  EXPECT_TRUE(box.statusText().contains(QStringLiteral("--signing-key")));
  switchOf(box)->click();
  EXPECT_EQ(box.choice(), (SigningChoice{true, kKeyB}));
  EXPECT_GE(changed.count(), 2);
}

TEST(SigningKeyBox, ExportWritesTheKeyForItsOwnerOnlyAndImportReadsItBack) {
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  const QString path = dir.filePath(QStringLiteral("robot.key"));
  SigningKeyBox source(tools(), SigningChoice{false, kKeyB});
  EXPECT_EQ(source.exportKey(path), QString());
  QFile file(path);
  ASSERT_TRUE(file.open(QIODevice::ReadOnly));
  EXPECT_EQ(QString::fromLatin1(file.readAll()), kKeyB + QLatin1Char('\n'));
  EXPECT_EQ(file.permissions() & (QFileDevice::ReadGroup | QFileDevice::ReadOther |
                                  QFileDevice::WriteGroup | QFileDevice::WriteOther),
            QFileDevice::Permissions());
  SigningKeyBox target(tools(), SigningChoice{});
  EXPECT_EQ(target.importKey(path), QString());
  EXPECT_EQ(target.choice().key, kKeyB);
}

TEST(SigningKeyBox, ImportingAFileThatIsNotAKeyKeepsTheKeyAndSaysWhy) {
  QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("notes.txt"));
  QFile file(path);
  ASSERT_TRUE(file.open(QIODevice::WriteOnly));
  file.write("hello\n");
  file.close();
  SigningKeyBox box(tools(), SigningChoice{true, kKeyA});
  const QString error = box.importKey(path);
  EXPECT_TRUE(error.contains(QStringLiteral("not 64 hex digits"))) << error.toStdString();
  EXPECT_EQ(box.choice(), (SigningChoice{true, kKeyA}));
  EXPECT_EQ(box.statusText(), error);
  EXPECT_FALSE(box.importKey(dir.filePath(QStringLiteral("missing.key"))).isEmpty());
}

TEST(SigningKeyBox, CopyPutsTheKeyTextOnTheClipboard) {
  SigningKeyBox box(tools(), SigningChoice{false, kKeyA});
  box.findChild<QPushButton*>(QStringLiteral("linkSigningCopy"))->click();
  EXPECT_EQ(QGuiApplication::clipboard()->text(), kKeyA);
}

TEST(ConnectionDialog, ShowsSigningOnlyWithKeyToolsAndHandsTheChoiceOverOnConnect) {
  ConnectionDialog plain(ConnectionDialogOptions{});
  EXPECT_EQ(plain.signingBox(), nullptr);

  ConnectionDialogOptions options;
  options.signing_tools = tools();
  options.signing = SigningChoice{false, kKeyA};
  std::optional<SigningChoice> saved;
  options.save_signing = [&saved](const SigningChoice& choice) { saved = choice; };
  {
    ConnectionDialog cancelled(options);
    ASSERT_NE(cancelled.signingBox(), nullptr);
    cancelled.signingBox()->setSigningEnabled(true);
    cancelled.reject();
    EXPECT_FALSE(saved) << "Cancel saved the signing choice";
  }
  ConnectionDialog dialog(options);
  dialog.setUrlText(QStringLiteral("tcp://127.0.0.1:5760"));
  dialog.signingBox()->setSigningEnabled(true);
  EXPECT_EQ(dialog.signing(), (SigningChoice{true, kKeyA}));
  dialog.accept();
  ASSERT_TRUE(saved);
  EXPECT_EQ(*saved, (SigningChoice{true, kKeyA}));
}

}  // namespace
}  // namespace irgs::widgets
