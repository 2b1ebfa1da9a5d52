// Tests of read_record (src/metrics/record_reader.cpp): a record's text read from a stream, as
// the CLI (from a file) and the browser explorer (from a dropped file's text) hand it over.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "oscidrum/error.hpp"
#include "oscidrum/oscidrum.hpp"

namespace oscidrum {
namespace {

RecordColumns read_text(const std::string& text, const RecordReading& o = {}) {
  std::istringstream in(text);
  return read_record(in, "record.csv", o);
}

std::string message_of(const std::string& text, const RecordReading& o = {}) {
  try {
    read_text(text, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A logger's record: a byte-order mark, a comment, 'Time [ms]', the accelerations in g with z
// positive up; read into the model's conventions (s, m/s^2, z positive down).
TEST(RecordReader, ByteOrderMarkUnitsAndAxisConventions) {
  const std::string text =
      "\xEF\xBB\xBF# logger 7\nTime [ms],acc_x [g],acc_z [g]\n0,1,0.5\n1,-1,0.25\n";
  RecordReading o;
  o.z_positive = "up";
  const RecordColumns r = read_text(text, o);
  EXPECT_EQ(r.t_column, "Time [ms]");  // the mark is not part of the first cell
  EXPECT_EQ(r.delimiter, "comma");
  ASSERT_EQ(r.t.size(), 2u);
  EXPECT_DOUBLE_EQ(r.t[1], 1e-3);
  EXPECT_DOUBLE_EQ(r.ddx_M[0], kStandardGravity);
  EXPECT_DOUBLE_EQ(r.ddz_M[1], -0.25 * kStandardGravity);
  EXPECT_DOUBLE_EQ(r.z_factor, -kStandardGravity);
  // x positive backward negates x_M''; units given override the header's.
  o.x_positive = "backward";
  o.units = "m/s2";
  const RecordColumns b = read_text(text, o);
  EXPECT_DOUBLE_EQ(b.ddx_M[0], -1.0);
  EXPECT_DOUBLE_EQ(b.ddz_M[0], -0.5);
}

// A European spreadsheet: semicolons and decimal commas; the model's own names (run --csv).
// An accelerometer's z reading keeps gravity: +1 g on average along an axis pointing up. Read as
// positive down (the default), that mean says the axis points the other way: a note says so and
// names the flag; read with --z-positive up (or without gravity in the record) nothing is said.
// A German logger's names: Zeit, Beschl. X / Beschleunigung Z (keys beschlx, beschleunigungz),
// and a longer one ending in the axis.
TEST(RecordReader, GermanChannelNames) {
  for (const std::string header : {"Zeit [ms];Beschl. X [g];Beschl. Z [g]",
                                   "Zeit [ms];Beschleunigung X [g];Beschleunigung Z [g]",
                                   "Zeit [ms];Beschl. Bandage X [g];Beschl. Bandage Z [g]"}) {
    SCOPED_TRACE(header);
    const RecordColumns r = read_text(header + "\n0;0,5;-0,25\n1;-0,5;0,25\n");
    ASSERT_EQ(r.t.size(), 2u);
    EXPECT_DOUBLE_EQ(r.t[1], 1e-3);
    EXPECT_DOUBLE_EQ(r.ddx_M[0], 0.5 * 9.80665);
    EXPECT_DOUBLE_EQ(r.ddz_M[0], -0.25 * 9.80665);
  }
}

TEST(RecordReader, GravityInTheZReadingHintsAtItsAxis) {
  const std::string with_gravity = "t,acc_x [g],acc_z [g]\n0,0.1,1.05\n0.001,-0.1,0.95\n";
  const auto hint = [](const RecordColumns& r) {
    int found = 0;
    for (const std::string& n : r.notes) found += n.find("about +1 g") != std::string::npos;
    return found;
  };
  const RecordColumns down = read_text(with_gravity);
  ASSERT_EQ(hint(down), 1);
  for (const std::string& n : down.notes)
    if (n.find("about +1 g") != std::string::npos) {
      EXPECT_NE(n.find("give --z-positive up"), std::string::npos) << n;
    }
  RecordReading up;
  up.z_positive = "up";
  EXPECT_EQ(hint(read_text(with_gravity, up)), 0);  // read as up: -1 g, as it should be
  EXPECT_EQ(hint(read_text("t,acc_x [g],acc_z [g]\n0,0.1,0.05\n0.001,-0.1,-0.05\n")), 0);
  // Read as up, a mean of -1 g in the file: the axis points down after all.
  const RecordColumns wrong =
      read_text("t,acc_x [g],acc_z [g]\n0,0.1,-1.05\n0.001,-0.1,-0.95\n", up);
  ASSERT_EQ(hint(wrong), 1);
  for (const std::string& n : wrong.notes)
    if (n.find("about +1 g") != std::string::npos) {
      EXPECT_NE(n.find("drop --z-positive up"), std::string::npos) << n;
    }
}

TEST(RecordReader, SemicolonsWithDecimalCommas) {
  const RecordColumns r = read_text("t[s];ddx_M[m/s^2];ddz_M[m/s^2]\n0,5;1,25;-2\n");
  EXPECT_EQ(r.delimiter, "semicolon");
  EXPECT_DOUBLE_EQ(r.t[0], 0.5);
  EXPECT_DOUBLE_EQ(r.ddx_M[0], 1.25);
  EXPECT_DOUBLE_EQ(r.ddz_M[0], -2.0);
  EXPECT_TRUE(r.notes.empty());  // read as the model writes it
}

// Messages name the record, the line and the column, or the option to give.
TEST(RecordReader, MessagesNameTheLineColumnOrOption) {
  EXPECT_NE(message_of("t,ax,az\n0,1,2\n0.001,1,oops\n")
                .find("record.csv:3: column 'az' must be a number; got 'oops'"),
            std::string::npos);
  EXPECT_NE(message_of("a,b,c\n0,1,2\n").find("no column looks like the time"), std::string::npos);
  EXPECT_NE(message_of("t,ax,az\n0,1\n").find("record.csv:2: 2 cells, but the header has 3"),
            std::string::npos);
  EXPECT_NE(message_of("# only comments\n").find("no data"), std::string::npos);
  EXPECT_NE(message_of("0,1,2\n").find("has no header line: give the time column"),
            std::string::npos);
}

}  // namespace
}  // namespace oscidrum
