// Tests of read_record (src/metrics/record_reader.cpp): a record's text read from a stream, as
// the CLI (from a file) and the browser explorer (from a dropped file's text) hand it over.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
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

// True when one of the reading's notes contains `what`.
bool has_note(const RecordColumns& r, const std::string& what) {
  return std::any_of(r.notes.begin(), r.notes.end(),
                     [&](const std::string& n) { return n.find(what) != std::string::npos; });
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
  // A logger in milli-g whose unit its header does not say (only its manual or a metadata line):
  // --units mg (there was no way to declare it).
  o.x_positive = "forward";
  o.units = "mg";
  const RecordColumns m = read_text("t,ax,az\n0,1000,500\n0.001,-1000,250\n", o);
  EXPECT_DOUBLE_EQ(m.ddx_M[0], kStandardGravity);
  EXPECT_DOUBLE_EQ(m.ddz_M[1], -0.25 * kStandardGravity);
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
  // Quoted decimal commas between commas (a spreadsheet in a German locale saved as CSV): said
  // so (the message was that the record had no header line); the same with ';' is read.
  EXPECT_NE(message_of("\"t\",\"ax\",\"az\"\n\"0,000\",\"-13,9\",\"0,6\"\n")
                .find("quoted numbers with a decimal comma (0,000) in a comma-separated file"),
            std::string::npos);
  EXPECT_DOUBLE_EQ(read_text("\"t\";\"ax\";\"az\"\n\"0,000\";\"-13,9\";\"0,6\"\n").ddx_M[0], -13.9);
}

// A three-axis logger's bare channel names X, Y, Z: x and z are the accelerations where no other
// column looks like one; beside acc_x, acc_z they are something else (a position) and not read.
TEST(RecordReader, BareAxisNamesWhereNothingElseMatches) {
  for (const std::string header : {"t,X,Y,Z,temp", "Time [s];X [g];Y [g];Z [g]", "t x z"}) {
    SCOPED_TRACE(header);
    const char d = header.find(';') != std::string::npos   ? ';'
                   : header.find(',') != std::string::npos ? ','
                                                           : ' ';
    const bool four = header.find('Y') != std::string::npos;
    std::string row0 =
        std::string("0") + d + "0.5" + d + (four ? std::string("7") + d : "") + "-0.25";
    // (x's mean not 1 g: a logger mounted with x vertical reads gravity there, and its Y, a
    // channel now, would make x the vertical.)
    std::string row1 =
        std::string("0.001") + d + "2.5" + d + (four ? std::string("7") + d : "") + "0.75";
    if (header.find("temp") != std::string::npos) {
      row0 += ",21";
      row1 += ",21";
    }
    if (d == ';') {  // a decimal comma
      std::replace(row0.begin(), row0.end(), '.', ',');
      std::replace(row1.begin(), row1.end(), '.', ',');
    }
    const RecordColumns r = read_text(header + "\n" + row0 + "\n" + row1 + "\n");
    ASSERT_EQ(r.t.size(), 2u);
    const double g = header.find("[g]") != std::string::npos ? 9.80665 : 1.0;
    EXPECT_DOUBLE_EQ(r.ddx_M[0], 0.5 * g);
    EXPECT_DOUBLE_EQ(r.ddz_M[1], 0.75 * g);
  }
  const RecordColumns r = read_text("t,x,z,acc_x,acc_z\n0,100,200,1,2\n0.001,101,201,3,4\n");
  EXPECT_DOUBLE_EQ(r.ddx_M[1], 3.0);
  EXPECT_DOUBLE_EQ(r.ddz_M[1], 4.0);
}

// A header written as a comment (numpy.savetxt's "# t,ax,az", Octave's "% time ax az"): the last
// comment before the data names the columns when it has as many as the data, none a number; a
// comment that does not (a description, or a line of numbers) leaves the record without a header.
TEST(RecordReader, AHeaderWrittenAsAComment) {
  for (const std::string text : {"# made by numpy\n# t,ax,az\n0,0.5,-0.25\n0.001,1.5,0.75\n",
                                 "% time ax az\n0 0.5 -0.25\n0.001 1.5 0.75\n",
                                 "//t;ax [g];az [g]\n0;0,5;-0,25\n0,001;1,5;0,75\n"}) {
    SCOPED_TRACE(text);
    const RecordColumns r = read_text(text);
    ASSERT_EQ(r.t.size(), 2u);  // the first line of data is data
    const double g = text.find("[g]") != std::string::npos ? 9.80665 : 1.0;
    EXPECT_DOUBLE_EQ(r.t[1], 0.001);
    EXPECT_DOUBLE_EQ(r.ddx_M[0], 0.5 * g);
    EXPECT_DOUBLE_EQ(r.ddz_M[1], 0.75 * g);
    EXPECT_TRUE(std::any_of(r.notes.begin(), r.notes.end(), [](const std::string& n) {
      return n.find("header from the comment") != std::string::npos;
    }));
  }
  for (const std::string text : {"# a record of the drum\n0,0.5,-0.25\n0.001,1.5,0.75\n",
                                 "# 1,2,3\n0,0.5,-0.25\n0.001,1.5,0.75\n"}) {
    SCOPED_TRACE(text);
    EXPECT_NE(message_of(text).find("has no header line"), std::string::npos) << message_of(text);
  }
}

// A time column without a unit is read in s; samples 1 s apart (a logger's ms read as s: 1
// sample/s resolves no excitation) are read in ms, as are samples 0.03 s apart (33 samples/s: under
// the 5 per period of 10 Hz), and 1000 apart in us, said with the flag that reads them in s;
// samples 0.015 s apart (66 samples/s) or 1 ms apart, a unit in the header or --t-units are read
// as they say.
TEST(RecordReader, TimeInMsOrUsWithoutAUnitIsReadSo) {
  const auto said = [](const RecordColumns& r, const std::string& what) {
    return std::any_of(r.notes.begin(), r.notes.end(),
                       [&](const std::string& n) { return n.find(what) != std::string::npos; });
  };
  const RecordColumns ms = read_text("t,ax,az\n0,1,2\n1,1,2\n2,1,2\n3,1,2\n");
  EXPECT_DOUBLE_EQ(ms.t[3], 0.003);
  EXPECT_EQ(ms.t_factor, 1e-3);
  EXPECT_TRUE(said(ms, "has no unit and is read in ms (1000 samples/s)"));
  EXPECT_TRUE(said(ms, "give --t-units s"));
  const RecordColumns us = read_text("t,ax,az\n0,1,2\n1000,1,2\n2000,1,2\n3000,1,2\n");
  EXPECT_DOUBLE_EQ(us.t[3], 0.003);
  EXPECT_TRUE(said(us, "has no unit and is read in us (1000 samples/s)"));
  const RecordColumns fast_ms = read_text("t,ax,az\n0,1,2\n0.03,1,2\n0.06,1,2\n0.09,1,2\n");
  EXPECT_DOUBLE_EQ(fast_ms.t[3], 0.09e-3);
  EXPECT_TRUE(said(fast_ms, "has no unit and is read in ms"));
  const RecordColumns slow = read_text("t,ax,az\n0,1,2\n0.015,1,2\n0.03,1,2\n0.045,1,2\n");
  EXPECT_DOUBLE_EQ(slow.t[3], 0.045);
  EXPECT_FALSE(said(slow, "has no unit"));
  for (const RecordColumns& r : {read_text("t,ax,az\n0,1,2\n0.001,1,2\n0.002,1,2\n0.003,1,2\n"),
                                 read_text("t [ms],ax,az\n0,1,2\n1,1,2\n2,1,2\n3,1,2\n")}) {
    EXPECT_DOUBLE_EQ(r.t[3], 0.003);
    EXPECT_FALSE(said(r, "has no unit"));
  }
  // Nanoseconds (a ROS message's stamp), without a unit and as the unit of time_ns.
  const RecordColumns ns = read_text("t,ax,az\n0,1,2\n1000000,1,2\n2000000,1,2\n3000000,1,2\n");
  EXPECT_DOUBLE_EQ(ns.t[3], 0.003);
  EXPECT_TRUE(said(ns, "has no unit and is read in ns (1000 samples/s)"));
  EXPECT_DOUBLE_EQ(read_text("time_ns,ax,az\n0,1,2\n500000,1,2\n").t[1], 5e-4);
  RecordReading o;
  o.t_units = "s";
  const RecordColumns given = read_text("t,ax,az\n0,1,2\n1,1,2\n2,1,2\n3,1,2\n", o);
  EXPECT_DOUBLE_EQ(given.t[3], 3.0);
  EXPECT_FALSE(said(given, "has no unit"));
}

// Lines ended by a lone CR (classic Mac OS text, Excel for Mac's CSV), by CR LF, or mixed; a
// spreadsheet's error values (#N/A, #DIV/0!) are missing values, their rows skipped and counted.
TEST(RecordReader, LoneCarriageReturnsAndSpreadsheetErrors) {
  for (const std::string& text : {std::string("t,ax,az\r0,1,2\r0.001,3,4\r0.002,5,6\r"),
                                  std::string("t,ax,az\r\n0,1,2\r\n0.001,3,4\r\n0.002,5,6"),
                                  std::string("t,ax,az\n0,1,2\r0.001,3,4\r\n0.002,5,6\n")}) {
    SCOPED_TRACE(text);
    const RecordColumns r = read_text(text);
    ASSERT_EQ(r.t.size(), 3u);
    EXPECT_DOUBLE_EQ(r.t[2], 0.002);
    EXPECT_DOUBLE_EQ(r.ddz_M[2], 6.0);
  }
  const RecordColumns errors =
      read_text("t,ax,az\n0,1,2\n0.001,#N/A,4\n0.002,5,#DIV/0!\n0.003,7,8\n");
  ASSERT_EQ(errors.t.size(), 2u);
  EXPECT_DOUBLE_EQ(errors.t[1], 0.003);
  EXPECT_TRUE(std::any_of(errors.notes.begin(), errors.notes.end(), [](const std::string& n) {
    return n.find("skipped 2 rows with a missing") != std::string::npos;
  }));
  // In the first cell: a row with a missing value, not a comment line. Dropped as a comment, it
  // lost its place in time under --rate: every later sample moved a step earlier.
  RecordReading by_rate;
  by_rate.rate = 1000.0;
  const RecordColumns first = read_text("ax,az\n1,2\n#N/A,4\n#DIV/0!,5\n7,8\n", by_rate);
  ASSERT_EQ(first.t.size(), 2u);
  EXPECT_DOUBLE_EQ(first.t[1], 0.003);
  EXPECT_DOUBLE_EQ(first.ddx_M[1], 7.0);
}

// A robot's inertial unit as ROS writes it. ROS 1's `rostopic echo -p`: the header a comment
// (%time), a text column in every row (frame_id: the first data row is no header for it), the
// stamps in ns since 1970, the channels fields of the message (field.linear_acceleration.x;
// PlotJuggler's export names them by their path, /imu/data/linear_acceleration/x). ROS 2's
// stamp in two columns, whole seconds and nanoseconds.
TEST(RecordReader, RosMessagesAsCsv) {
  const RecordColumns ros1 = read_text(
      "%time,field.header.seq,field.header.frame_id,field.angular_velocity.x,"
      "field.linear_acceleration.x,field.linear_acceleration.y,field.linear_acceleration.z\n"
      "1764752400000000000,0,imu_link,0.0,1.5,0.1,-9.8\n"
      "1764752400001000000,1,imu_link,0.0,2.5,0.1,-9.7\n"
      "1764752400002000000,2,imu_link,0.0,3.5,0.1,-9.6\n"
      "1764752400003000000,3,imu_link,0.0,4.5,0.1,-9.5\n");
  ASSERT_EQ(ros1.t.size(), 4u);  // the first data row is data
  EXPECT_EQ(ros1.t_column, "time");
  EXPECT_NEAR(ros1.t[3] - ros1.t[0], 0.003, 1e-6);  // (the stamps' doubles: 2.4e-7 s apart)
  EXPECT_NEAR(ros1.t[0], 1764752400.0, 1e-6);
  EXPECT_EQ(ros1.x_column, "field.linear_acceleration.x");
  EXPECT_EQ(ros1.z_column, "field.linear_acceleration.z");
  EXPECT_DOUBLE_EQ(ros1.ddx_M[3], 4.5);
  const RecordColumns juggler = read_text(
      "__time,/imu/data/linear_acceleration/x,/imu/data/linear_acceleration/z\n"
      "1764752400.000,1,2\n1764752400.001,3,4\n");
  EXPECT_EQ(juggler.x_column, "/imu/data/linear_acceleration/x");
  EXPECT_DOUBLE_EQ(juggler.ddz_M[1], 4.0);
  const RecordColumns ros2 = read_text(
      "header.stamp.sec,header.stamp.nanosec,linear_acceleration.x,linear_acceleration.z\n"
      "1764752400,999000000,1,2\n1764752401,0,3,4\n1764752401,1000000,5,6\n");
  ASSERT_EQ(ros2.t.size(), 3u);
  EXPECT_NEAR(ros2.t[1] - ros2.t[0], 0.001, 1e-6);
  EXPECT_NEAR(ros2.t[2] - ros2.t[0], 0.002, 1e-6);
  EXPECT_EQ(ros2.t_column, "header.stamp.sec + header.stamp.nanosec x 1e-9");
  const RecordColumns ros1_stamp =
      read_text("stamp.secs,stamp.nsecs,ax,az\n10,999000000,1,2\n11,0,3,4\n");
  EXPECT_NEAR(ros1_stamp.t[1] - ros1_stamp.t[0], 0.001, 1e-12);
  // Its units are the columns': a slow logger's stamps are not rescaled by their step.
  const RecordColumns slow =
      read_text("stamp.sec,stamp.nanosec,ax,az\n10,0,1,2\n10,100000000,3,4\n10,200000000,5,6\n");
  EXPECT_NEAR(slow.t[2] - slow.t[0], 0.2, 1e-12);
  // A text column in the data does not make its first row a header where another line is one.
  const RecordColumns labelled = read_text("t,ax,az,label\n0,1,2,a\n0.001,3,4,a\n");
  ASSERT_EQ(labelled.t.size(), 2u);
  EXPECT_DOUBLE_EQ(labelled.ddx_M[0], 1.0);
  // Nor does a first data row of missing values alone.
  const RecordColumns first_missing = read_text("t,ax,az\nNaN,NaN,NaN\n0,1,2\n0.001,3,4\n");
  ASSERT_EQ(first_missing.t.size(), 2u);
  EXPECT_DOUBLE_EQ(first_missing.ddz_M[1], 4.0);
}

// Time columns named otherwise than t, time, zeit, timestamp: by a name ending in "time" or
// "zeit", by their unit alone (then read in it), by a word for it, by a date (only where no
// other column names the time: beside an Uhrzeit, a Datum holds the day); and a spreadsheet's
// serial date (days) without a unit.
TEST(RecordReader, TimeColumnsNamedOtherwiseAndSerialDates) {
  const auto said = [](const RecordColumns& r, const std::string& what) {
    return std::any_of(r.notes.begin(), r.notes.end(),
                       [&](const std::string& n) { return n.find(what) != std::string::npos; });
  };
  const std::string rows_s = "0,1,2\n0.001,1,2\n0.002,1,2\n0.003,1,2\n";
  for (const std::string name :
       {"Relative Time", "Record Time", "Sample time", "DateTime", "Uhrzeit", "Messzeit",
        "Laufzeit", "Datum/Zeit", "Time of day", "Sekunden", "Duration", "s", "Date"}) {
    SCOPED_TRACE(name);
    const RecordColumns r = read_text(name + ",ax,az\n" + rows_s);
    EXPECT_EQ(r.t_column, name);
    EXPECT_DOUBLE_EQ(r.t[3], 0.003);
  }
  for (const auto& [name, rows] :
       {std::pair<std::string, std::string>{"ms", "0,1,2\n1,1,2\n2,1,2\n3,1,2\n"},
        {"millis", "10,1,2\n11,1,2\n12,1,2\n13,1,2\n"},
        {"us", "0,1,2\n1000,1,2\n2000,1,2\n3000,1,2\n"},
        {"micros", "0,1,2\n1000,1,2\n2000,1,2\n3000,1,2\n"}}) {
    SCOPED_TRACE(name);
    const RecordColumns r = read_text(name + ",ax,az\n" + rows);
    EXPECT_EQ(r.t_column, name);
    EXPECT_NEAR(r.t[3] - r.t[0], 0.003, 1e-15);
    EXPECT_FALSE(said(r, "has no unit"));  // the name is the unit
  }
  // A name of the first kind wins over the others; a date only where nothing else names a time.
  EXPECT_EQ(read_text("Datum,Uhrzeit,ax,az\n1,0,1,2\n1,0.001,1,2\n1,0.002,1,2\n").t_column,
            "Uhrzeit");
  EXPECT_EQ(read_text("Relative Time,t,ax,az\n5,0,1,2\n5,0.001,1,2\n5,0.002,1,2\n").t_column, "t");
  // Serial dates: 1 kHz as days since 1899-12-30, in s from the first row, with a note.
  std::string serial = "Date,ax,az\n";
  for (int i = 0; i < 6; ++i) {
    char line[64];
    std::snprintf(line, sizeof line, "%.12f,1,2\n", 46174.5 + i / 86400000.0);
    serial += line;
  }
  const RecordColumns days = read_text(serial);
  EXPECT_EQ(days.t.front(), 0.0);
  // A double holds 46174.5 days to 7.3e-12 days (0.63 us): each row time is that close.
  EXPECT_NEAR(days.t[5], 0.005, 1e-6);
  EXPECT_EQ(days.t_factor, 86400.0);
  EXPECT_TRUE(said(days, "read in days, a spreadsheet's serial date"));
  RecordReading in_s;
  in_s.t_units = "s";
  EXPECT_NEAR(read_text(serial, in_s).t[5], 46174.5 + 5 / 86400000.0, 1e-9);
  // Under a day, steps of under a microsecond are a fast simulation's seconds, not days.
  const RecordColumns fast = read_text("t,ax,az\n0,1,2\n1e-8,1,2\n2e-8,1,2\n3e-8,1,2\n");
  EXPECT_DOUBLE_EQ(fast.t[3], 3e-8);
  EXPECT_FALSE(said(fast, "days"));
  // A sample number is not a time: the message names --rate.
  try {
    (void)read_text("Index,ax,az\n0,1,2\n1,1,2\n2,1,2\n");
    ADD_FAILURE() << "an index read as the time";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no column looks like the time"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("--rate"), std::string::npos);
  }
  // A time stamp in German, Dutch, Spanish and French, and a German date with a decimal comma.
  for (const char* name : {"Zeitstempel", "Tijdstempel", "Marca de tiempo", "Horodatage"})
    EXPECT_DOUBLE_EQ(read_text(std::string(name) + ",ax,az\n0,1,2\n0.001,3,4\n").t[1], 0.001)
        << name;
  const RecordColumns german =
      read_text("Zeitstempel;ax;az\n03.12.2026 10:15:30,000;1,5;2\n03.12.2026 10:15:30,001;3;4\n");
  ASSERT_EQ(german.t.size(), 2u);
  EXPECT_NEAR(german.t[1], 0.001, 1e-12);
  EXPECT_DOUBLE_EQ(german.ddx_M[0], 1.5);
}

// What files joined or cut short hold: a header repeated between the parts is skipped; lines
// after the data that are not rows (a footer, a last row cut short) are skipped with a note, up
// to 20 of them and only where no row follows; a pipe-separated record is read.
TEST(RecordReader, RepeatedHeadersFootersAndPipes) {
  const auto said = [](const RecordColumns& r, const std::string& what) {
    return std::any_of(r.notes.begin(), r.notes.end(),
                       [&](const std::string& n) { return n.find(what) != std::string::npos; });
  };
  const std::string rows = "0,1,2\n0.001,1,2\n0.002,1,2\n0.003,1,2\n";
  const RecordColumns joined =
      read_text("t,ax,az\n" + rows + "t,ax,az\n0.004,1,2\nT, AX ,az\n0.005,1,2\n");
  EXPECT_EQ(joined.t.size(), 6u);
  EXPECT_DOUBLE_EQ(joined.t[5], 0.005);
  EXPECT_TRUE(said(joined, "skipped 2 lines repeating the header (the first at line 6"));
  const RecordColumns footer = read_text("t,ax,az\n" + rows + "End of data\nSamples: 4\n");
  EXPECT_EQ(footer.t.size(), 4u);
  EXPECT_TRUE(said(footer, "skipped 2 lines after the data, from line 6 ('End of data')"));
  const RecordColumns cut = read_text("t,ax,az\n" + rows + "0.004,1.2");
  EXPECT_EQ(cut.t.size(), 4u);
  EXPECT_TRUE(said(cut, "a last row cut short"));
  // A refused line with rows after it is an error, as it was; so are more than 20 such lines
  // and a last line with the header's cells and a number (a row with a bad value).
  for (const std::string& text : {std::string("t,ax,az\n0,1,2\n0.001,x,2\n0.002,1,2\n0.003,1,2\n"),
                                  std::string("t,ax,az\n0,1,2\n0.001,1,2\n0.002,1\n0.003,1,2\n"),
                                  "t,ax,az\n" + rows + "0.004,x,2\n"}) {
    SCOPED_TRACE(text.substr(0, 60));
    EXPECT_THROW((void)read_text(text), Error);
  }
  std::string long_footer = "t,ax,az\n" + rows;
  for (int i = 0; i < 21; ++i) long_footer += "summary line\n";
  EXPECT_THROW((void)read_text(long_footer), Error);
  // Only footer lines: no rows, the first refusal.
  EXPECT_THROW((void)read_text("t,ax,az\nEnd of data\nSamples: 0\n"), Error);
  const RecordColumns pipes = read_text("t|ax|az\n0|1,5|2\n0.001|1|2\n0.002|1|2\n");
  EXPECT_EQ(pipes.delimiter, "pipe");
  EXPECT_DOUBLE_EQ(pipes.ddx_M[0], 1.5);  // a decimal comma, as beside ; and tab
  EXPECT_DOUBLE_EQ(pipes.t[2], 0.002);
}

// The path length along easting and northing does not count the fixes' scatter as travel: a
// roller standing still with 2 cm of RTK noise at 10 fixes per second went 3.3 m in 10 s, summed
// fix to fix. Standing 8 s, then 10 m east at 1 m/s, then standing 2 s.
TEST(RecordReader, TheFixesScatterIsNoTravel) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::string text = "t,ax,az,Easting,Northing\n";
  char row[160];
  for (int i = 0; i < 2000; ++i) {  // 100 rows per second, a fix every tenth
    const double t = 0.01 * i;
    const double along = std::clamp(t - 8.0, 0.0, 10.0);
    if (i % 10 == 0)
      std::snprintf(row, sizeof row, "%.2f,1,2,%.4f,%.4f\n", t, 600000.0 + along + noise(rng),
                    5340000.0 + noise(rng));
    else
      std::snprintf(row, sizeof row, "%.2f,1,2,,\n", t);
    text += row;
  }
  const RecordColumns r = read_text(text);
  ASSERT_EQ(r.position.size(), 2000u);
  EXPECT_LT(r.position[790], 0.1);                              // standing: at most a few cm
  EXPECT_NEAR(r.position[1399] - r.position[900], 4.99, 0.15);  // 5 m of the 10
  EXPECT_NEAR(r.position.back(), 10.0, 0.15);
  // The same track as a logger writes it with its own interpolation between the fixes on every
  // row, to the mm (every row a new value: summed row to row, it read metres while standing).
  std::string filled = "t,ax,az,Easting,Northing\n";
  for (std::size_t i = 0; i < 2000; ++i) {
    std::snprintf(row, sizeof row, "%.2f,1,2,%.3f,%.3f\n", r.t[i], r.east[i], r.north[i]);
    filled += row;
  }
  const RecordColumns f = read_text(filled);
  ASSERT_EQ(f.position.size(), 2000u);
  EXPECT_LT(f.position[790], 0.1);
  EXPECT_NEAR(f.position[1399] - f.position[900], 4.99, 0.15);
  EXPECT_NEAR(f.position.back(), 10.0, 0.15);
}

// A logger's GNSS columns are recognised without flags (Latitude/Longitude, else Easting/
// Northing); a fix every few rows fills the rows between in time; columns that are no
// coordinates in degrees, or not numbers, are dropped with a note (given by the flags, they are
// an error). A speed's or position's unit in its header is read (km/h, km).
TEST(RecordReader, GnssColumnsFixesBetweenRowsAndUnitsOfSpeed) {
  const auto said = [](const RecordColumns& r, const std::string& what) {
    return std::any_of(r.notes.begin(), r.notes.end(),
                       [&](const std::string& n) { return n.find(what) != std::string::npos; });
  };
  const RecordColumns r = read_text(
      "Time [s],Acc X,Acc Z,Latitude,Longitude\n0,1,2,48.0,16.0\n0.001,1,2,,\n0.002,1,2,,\n"
      "0.003,1,2,,\n0.004,1,2,48.4,16.8\n0.005,1,2,,\n");
  ASSERT_EQ(r.t.size(), 6u);  // no row skipped for an empty fix
  ASSERT_EQ(r.lat.size(), 6u);
  EXPECT_NEAR(r.lat[1], 48.1, 1e-12);
  EXPECT_NEAR(r.lon[3], 16.6, 1e-12);
  EXPECT_DOUBLE_EQ(r.lat[5], 48.4);  // held after the last fix
  EXPECT_TRUE(said(r, "latitude and longitude from the columns 'Latitude' and 'Longitude'"));
  EXPECT_TRUE(said(r, "2 of the 6 rows hold a GNSS fix"));
  const RecordColumns before = read_text(
      "t,ax,az,lat,lon\n0,1,2,,\n0.001,1,2,48.2,16.3\n0.002,1,2,48.2,16.3\n0.003,1,2,48.2,16.3\n");
  EXPECT_DOUBLE_EQ(before.lat[0], 48.2);  // held before the first
  const RecordColumns utm = read_text(
      "t,ax,az,Rechtswert,Hochwert [km]\n0,1,2,600000,5340\n0.001,1,2,600003,5340.004\n"
      "0.002,1,2,600006,5340.008\n");
  ASSERT_EQ(utm.east.size(), 3u);
  EXPECT_NEAR(utm.north[2], 5340008.0, 1e-6);
  EXPECT_NEAR(utm.position[2], 10.0, 1e-6);  // 3 m east and 4 m north a row: 5 m along the track
  for (const std::string& text :
       {std::string("t,ax,az,Lat,Lon\n0,1,2,4812.5,1622.1\n0.001,1,2,4812.5,1622.1\n"
                    "0.002,1,2,4812.5,1622.1\n"),
        std::string("t,ax,az,Lat,Lon\n0,1,2,48N,16E\n0.001,1,2,48N,16E\n0.002,1,2,48N,16E\n"),
        std::string("t,ax,az,Lat,Lon\n0,1,2,,\n0.001,1,2,,\n0.002,1,2,,\n")}) {
    SCOPED_TRACE(text);
    const RecordColumns dropped = read_text(text);
    EXPECT_EQ(dropped.t.size(), 3u);
    EXPECT_TRUE(dropped.lat.empty());
    EXPECT_TRUE(said(dropped, "position: the columns 'Lat' and 'Lon'"));
  }
  // Both pairs given, fixes every few rows: the projected pair is filled between its fixes as
  // well (it stayed NaN there, and with it every window's position, easting and northing).
  RecordReading both;
  both.lat_col = "lat", both.lon_col = "lon", both.east_col = "E", both.north_col = "N";
  const RecordColumns pairs = read_text(
      "t,ax,az,lat,lon,E,N\n0,1,2,48.0,16.0,600000,5340000\n0.001,1,2,,,,\n"
      "0.002,1,2,48.2,16.2,600006,5340008\n",
      both);
  ASSERT_EQ(pairs.east.size(), 3u);
  EXPECT_NEAR(pairs.lat[1], 48.1, 1e-12);
  EXPECT_NEAR(pairs.east[1], 600003.0, 1e-6);
  EXPECT_NEAR(pairs.north[1], 5340004.0, 1e-6);
  EXPECT_NEAR(pairs.position[2], 10.0, 1e-6);
  RecordReading chosen;
  chosen.lat_col = "Lat";
  chosen.lon_col = "Lon";
  EXPECT_THROW(
      (void)read_text("t,ax,az,Lat,Lon\n0,1,2,4812.5,1622.1\n0.001,1,2,4812.5,1622.1\n", chosen),
      Error);
  // Two latitude-like columns: none chosen.
  EXPECT_TRUE(
      read_text("t,ax,az,lat,gps_lat,lon\n0,1,2,48,48,16\n0.001,1,2,48,48,16\n").lat.empty());
  // A speed logged at the GNSS rate (empty cells between): the rows are kept (99 % of a pass's
  // rows were dropped for them) and the speed between interpolated in time.
  RecordReading sparse_speed;
  sparse_speed.speed_col = "v";
  const RecordColumns sv =
      read_text("t,ax,az,v\n0,1,2,1\n0.001,1,2,\n0.002,1,2,3\n0.003,1,2,\n", sparse_speed);
  ASSERT_EQ(sv.t.size(), 4u);
  EXPECT_NEAR(sv.position[3], 1e-3 * (1.5 + 2.5 + 3.0), 1e-15);  // speeds 1, 2, 3, 3 m/s
  EXPECT_TRUE(said(sv, "2 of the 4 rows hold a value in 'v'"));
  EXPECT_THROW((void)read_text("t,ax,az,v\n0,1,2,\n1,1,2,\n", sparse_speed), Error);
  RecordReading speed;
  speed.speed_col = "Speed [km/h]";
  const RecordColumns kmh =
      read_text("t [s],ax,az,Speed [km/h]\n0,1,2,3.6\n1,1,2,3.6\n2,1,2,3.6\n", speed);
  EXPECT_NEAR(kmh.position[2], 2.0, 1e-12);  // 1 m/s for 2 s
  speed.speed_col = "Speed [knots]";
  EXPECT_THROW((void)read_text("t,ax,az,Speed [knots]\n0,1,2,3.6\n1,1,2,3.6\n", speed), Error);
  RecordReading pos;
  pos.pos_col = "Station (km)";
  EXPECT_NEAR(read_text("t [s],ax,az,Station (km)\n0,1,2,1.5\n1,1,2,1.501\n", pos).position[1],
              1501.0, 1e-9);
}

// A European spreadsheet's CSV in Windows-1252 / Latin-1 (not UTF-8): its units m/s\xB2 and
// \xB5s are read as meant, with a note; a UTF-8 file's are as before.
TEST(RecordReader, Windows1252TextIsReadAsItsCharacters) {
  const RecordColumns r = read_text(
      "Zeit [\xB5s];Beschl. X [m/s\xB2];Beschl. Z [m/s\xB2];Temperatur [\xB0"
      "C]\n"
      "0;1,5;2;21\n1000;1;2;21\n2000;1;2;21\n");
  ASSERT_EQ(r.t.size(), 3u);
  EXPECT_DOUBLE_EQ(r.t[2], 0.002);
  EXPECT_DOUBLE_EQ(r.ddx_M[0], 1.5);
  EXPECT_EQ(r.x_column, "Beschl. X [m/s\xC2\xB2]");
  EXPECT_TRUE(std::any_of(r.notes.begin(), r.notes.end(), [](const std::string& n) {
    return n.find("read as Windows-1252 / Latin-1 text: line 1 is not UTF-8") != std::string::npos;
  }));
  const RecordColumns utf8 =
      read_text("t [\xC2\xB5s],ax [m/s\xC2\xB2],az [m/s\xC2\xB2]\n0,1,2\n1000,1,2\n2000,1,2\n");
  EXPECT_DOUBLE_EQ(utf8.t[2], 0.002);
  EXPECT_TRUE(std::none_of(utf8.notes.begin(), utf8.notes.end(), [](const std::string& n) {
    return n.find("Latin-1") != std::string::npos;
  }));
}

// The paper's notation and others for the drum centre's accelerations: x_M'' (beside the
// displacement x_M), x'', x double dot, x prime prime, xM_acc, acc_hor / acc_vert, hor / vert,
// acc_long (the direction of travel).
TEST(RecordReader, NotationsOfASecondDerivative) {
  for (const std::string header : {"t,x_M,x_M'',z_M'',z_M",
                                   "t,x'',z''",
                                   "t,x_dd,z_dd",
                                   "t,xpp,zpp",
                                   "t,xM_acc,zM_acc",
                                   "time,acc_hor,acc_vert",
                                   "time,hor,vert",
                                   "timestamp,acc_long,acc_vert",
                                   "t,a_long,a_v",
                                   "t,longitudinal,vertical",
                                   "timestamp,acc_h,acc_v",
                                   "t,ax_M,az_M",
                                   "t,x_M [m],x_M'' [g],z_M'' [g],z_M [m]",
                                   "t,ddot{x}_M,ddot{z}_M",
                                   "t,ddot_x,ddot_z",
                                   "t,d2x,d2z",
                                   "t,d2x_M,d2z_M",
                                   "t,d2x/dt2,d2z/dt2",
                                   "t,d^2x_M/dt^2,d^2z_M/dt^2",
                                   "t,x''(t),z''(t)",
                                   "t,ax_centre,az_centre",
                                   "t,acc_x_center,acc_z_center",
                                   "t,acc_x_M,acc_z_M",
                                   "t,accel_x_M,accel_z_M",
                                   "t,x_dd_M,z_dd_M",
                                   "t,xddot_M,zddot_M",
                                   "t,x_pp_M,z_pp_M",
                                   "t,x_dotdot,z_dotdot",
                                   "t,x_M_dotdot,z_M_dotdot",
                                   "t,x_2dot,z_2dot",
                                   "t,a_M_x,a_M_z",
                                   "t,acc_M_x,acc_M_z",
                                   "t,linear_acceleration_x,linear_acceleration_z",
                                   "t,A1_X,A1_Z",
                                   "t,a1x,a1z",
                                   "t,Sensor1_AccX,Sensor1_AccZ",
                                   "t,S1.ax,S1.az",
                                   "t,Ch1_AccX,Ch2_AccZ",
                                   "t,Kanal 3 Beschl. X,Kanal 3 Beschl. Z"}) {
    SCOPED_TRACE(header);
    const bool four = std::count(header.begin(), header.end(), ',') == 4;
    const std::string rows =
        four ? "0,9,0.5,-0.25,9\n0.001,9,1.5,0.75,9\n" : "0,0.5,-0.25\n0.001,1.5,0.75\n";
    const RecordColumns r = read_text(header + "\n" + rows);
    ASSERT_EQ(r.t.size(), 2u);
    const double g = header.find("[g]") != std::string::npos ? 9.80665 : 1.0;
    EXPECT_DOUBLE_EQ(r.ddx_M[0], 0.5 * g);
    EXPECT_DOUBLE_EQ(r.ddz_M[1], 0.75 * g);
  }
  // A numbered sensor's bare axis is an accelerometer's only where its word says so (s1x may be
  // a displacement).
  EXPECT_THROW((void)read_text("t,s1x,s1z\n0,1,2\n0.001,1,2\n"), Error);
  EXPECT_THROW((void)read_text("t,A1_X,A1_Z,A2_X,A2_Z\n0,1,2,1,2\n0.001,1,2,1,2\n"), Error);
}

// A column named for the drum (ax_drum, drum acc. x, Bandage, Trommel) is read as its
// acceleration, and chosen over one that does not name it (a frame's beside the drum's).
TEST(RecordReader, ColumnsNamedForTheDrum) {
  for (const std::string header :
       {"t,ax_drum,az_drum", "time [s],drum acc. x [m/s2],drum acc. z [m/s2]",
        "Zeit,Beschl. Bandage X,Beschl. Bandage Z", "t,Trommel a_x,Trommel a_z",
        "t,acc_x,acc_z,acc_x_drum,acc_z_drum", "t,drum_ax,drum_az,ax,az",
        "Time (s),Drum X (g),Drum Z (g)", "t,Bandage X,Bandage Z", "t,Vib X,Vib Z",
        "t,vibration_x [m/s^2],vibration_z [m/s^2]"}) {
    SCOPED_TRACE(header);
    const bool four = std::count(header.begin(), header.end(), ',') == 4;
    const bool drum_first = header.rfind("t,drum_", 0) == 0;
    const std::string rows = !four        ? "0,0.5,-0.25\n0.001,1.5,0.75\n"
                             : drum_first ? "0,0.5,-0.25,9,9\n0.001,1.5,0.75,9,9\n"
                                          : "0,9,9,0.5,-0.25\n0.001,9,9,1.5,0.75\n";
    const RecordColumns r = read_text(header + "\n" + rows);
    ASSERT_EQ(r.t.size(), 2u);
    const double g = header.find("(g)") != std::string::npos ? kStandardGravity : 1.0;
    EXPECT_DOUBLE_EQ(r.ddx_M[0], 0.5 * g);
    EXPECT_DOUBLE_EQ(r.ddz_M[1], 0.75 * g);
  }
  // A vibration channel in a velocity's unit is not read as an acceleration.
  EXPECT_THROW(read_text("t,Vib X [mm/s],Vib Z [mm/s]\n0,0.5,-0.25\n0.001,1.5,0.75\n"), Error);
  // Two drums' columns: still a choice for the user.
  EXPECT_THROW(read_text("t,ax_drum1,ax_drum2,az\n0,1,2,3\n"), Error);
}

// A logger's clock times in the time column: t in s from the first row's, across midnight, a
// month's end and a leap day, with the dates in ISO or German order, a zone, or no date at all.
TEST(RecordReader, ClockTimesInTheTimeColumn) {
  const auto times = [](const std::string& text) { return read_text(text).t; };
  const std::vector<double> iso = times(
      "Timestamp,ax,az\n2024-02-28T23:59:59.500Z,1,2\n2024-02-29T00:00:00.750Z,1,2\n"
      "2024-03-01T00:00:00.500Z,1,2\n");
  ASSERT_EQ(iso.size(), 3u);
  EXPECT_DOUBLE_EQ(iso[0], 0.0);
  EXPECT_DOUBLE_EQ(iso[1], 1.25);
  EXPECT_DOUBLE_EQ(iso[2], 86401.0);  // 2024 is a leap year: Feb 29 lies between
  const std::vector<double> plain_year =
      times("t;ax;az\n28.02.2023 23:59:59,5;1;2\n01.03.2023 00:00:00,5;1;2\n");
  ASSERT_EQ(plain_year.size(), 2u);
  EXPECT_DOUBLE_EQ(plain_year[1], 1.0);  // 2023 is not
  // A zone: 10:00:00+02:00 is 08:00:00Z.
  const std::vector<double> zoned =
      times("time,ax,az\n2026-05-12 08:00:00Z,1,2\n2026-05-12 10:00:01+02:00,1,2\n");
  EXPECT_DOUBLE_EQ(zoned[1], 1.0);
  // No date: midnight passes when the clock falls back by more than 12 hours.
  const std::vector<double> clock =
      times("time\tax\taz\n23:59:59.999\t1\t2\n00:00:00.001\t1\t2\n9:00:00\t1\t2\n");
  ASSERT_EQ(clock.size(), 3u);
  EXPECT_NEAR(clock[1], 0.002, 1e-12);
  EXPECT_NEAR(clock[2], 9 * 3600.0 + 0.001, 1e-9);
  // Without a header line too (the clock times make the first line data; its columns given).
  RecordReading columns;
  columns.t_col = "1";
  columns.x_col = "2";
  columns.z_col = "3";
  const RecordColumns headless =
      read_text("2026-05-12T08:00:00,1,2\n2026-05-12T08:00:00.001,1,2\n", columns);
  ASSERT_EQ(headless.t.size(), 2u);
  EXPECT_DOUBLE_EQ(headless.t[1], 0.001);
  // The note says how t was read.
  const RecordColumns r = read_text("Timestamp,ax,az\n2026-05-12 08:00:00,1,2\n");
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes.front().find("clock times (with dates)"), std::string::npos);
  // A date that is not one, and a row without the first row's date, are errors at their line.
  EXPECT_NE(message_of("t,ax,az\n2026-13-01 08:00:00,1,2\n").find("must be a number or a clock"),
            std::string::npos);
  EXPECT_NE(
      message_of("t,ax,az\n2026-05-12 08:00:00,1,2\n08:00:01,1,2\n")
          .find("record.csv:3: column 't' must be a clock time like the first row's, with a date"),
      std::string::npos);
  // US spreadsheets: M/D/YYYY with AM/PM (12 AM is midnight, 12 PM noon), D/M/YYYY where the
  // first field is above 12, one-digit fields.
  const std::vector<double> us = times(
      "Time,ax,az\n12/31/2025 11:59:59.5 PM,1,2\n1/1/2026 12:00:00.25 AM,1,2\n"
      "1/1/2026 12:00:00.25 PM,1,2\n");
  ASSERT_EQ(us.size(), 3u);
  EXPECT_DOUBLE_EQ(us[1], 0.75);
  EXPECT_DOUBLE_EQ(us[2], 0.75 + 12 * 3600.0);
  EXPECT_DOUBLE_EQ(times("t,ax,az\n13/1/2026 08:00:00,1,2\n14/1/2026 08:00:00,1,2\n")[1], 86400.0);
  EXPECT_DOUBLE_EQ(times("t,ax,az\n1-2-2026 08:00:00,1,2\n1-3-2026 08:00:00,1,2\n")[1],
                   86400.0);  // M-D-YYYY: January 2 and 3
  // Elapsed minutes and seconds with a fraction (MM:SS.fff); a clock of the hour passes it.
  const std::vector<double> elapsed =
      times("Time,ax,az\n01:01.500,1,2\n01:01.501,1,2\n75:00.0,1,2\n");
  EXPECT_NEAR(elapsed[1], 0.001, 1e-12);
  EXPECT_DOUBLE_EQ(elapsed[2], 75 * 60.0 - 61.5);
  EXPECT_NEAR(times("Time,ax,az\n59:59.999,1,2\n00:00.001,1,2\n")[1], 0.002, 1e-12);
  // HH:MM without seconds is not a time of a record; 13 PM is no time.
  EXPECT_NE(message_of("t,ax,az\n10:31,1,2\n10:32,1,2\n").find("must be a number or a clock"),
            std::string::npos);
  EXPECT_NE(message_of("t,ax,az\n1/1/2026 13:00:00 PM,1,2\n").find("must be a number or a clock"),
            std::string::npos);
}

// A logger's dropouts: rows with an empty cell, NaN, NA or a dash in a column read are skipped
// and counted in a note (the gap gate judges the windows they fall in); columns not read may hold
// anything. A record with nothing but such rows is an error that says so.
TEST(RecordReader, RowsWithMissingValuesAreSkippedAndCounted) {
  const RecordColumns r = read_text(
      "t,ax,az,comment\n0,1,2,x\n0.001,,2,\n0.002,NaN,2,\n0.003,1,NA,\n0.004,1,-,\n"
      "0.005,1,inf,\n0.006,3,4,\n");
  ASSERT_EQ(r.t.size(), 2u);
  EXPECT_DOUBLE_EQ(r.t[1], 0.006);
  EXPECT_DOUBLE_EQ(r.ddx_M[1], 3.0);
  int notes = 0;
  for (const std::string& n : r.notes)
    notes += n.find("skipped 5 rows with a missing or non-finite value (the first at line 3)") !=
             std::string::npos;
  EXPECT_EQ(notes, 1);
  EXPECT_NE(message_of("t,ax,az\n0,,1\n1,2,\n").find("every data row (2) has a missing"),
            std::string::npos);
  // A cell that is neither a number nor missing is still an error.
  EXPECT_NE(
      message_of("t,ax,az\n0,1,2\n1,abc,2\n").find("record.csv:3: column 'ax' must be a number"),
      std::string::npos);
}

// A record without a time column, at a known sampling rate: t from the data row, a skipped row
// keeping its place in time; the rate and a time column together, or a rate that is not one, are
// refused.
TEST(RecordReader, TimeFromTheRowNumberAtAGivenRate) {
  RecordReading o;
  o.rate = 1000.0;
  const RecordColumns r = read_text("Sample,ax,az\n0,1,2\n1,,2\n2,3,4\n", o);
  ASSERT_EQ(r.t.size(), 2u);
  EXPECT_DOUBLE_EQ(r.t[0], 0.0);
  EXPECT_DOUBLE_EQ(r.t[1], 0.002);
  EXPECT_DOUBLE_EQ(r.ddx_M[1], 3.0);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes.front().find("from the row number at --rate 1000 Hz"), std::string::npos);
  o.t_col = "Sample";
  EXPECT_NE(message_of("Sample,ax,az\n0,1,2\n", o).find("not both"), std::string::npos);
  o.t_col.clear();
  for (double bad : {-1.0, 0.5, 1.1e7, 1e308, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    o.rate = bad;
    EXPECT_NE(message_of("Sample,ax,az\n0,1,2\n", o).find("--rate) must be in [1, 1e7] Hz"),
              std::string::npos)
        << bad;
  }
}

// Milli-g (MEMS accelerometers), feet per second squared, and microseconds written with the
// Greek mu as well as the micro sign (both were read as seconds: the unit's key keeps ASCII
// letters only, and "\xC2\xB5s" became "s").
// Another implementation's numbers: a Fortran program's D exponents, a leading '+', a bare
// decimal point.
TEST(RecordReader, FortranExponentsAndOtherNumberForms) {
  const RecordColumns r =
      read_text("t,ax,az\n0.0D+00,1.25D+01,-2.5d-1\n1.0D-03,+.5,5.\n2.0D-3,1,2\n");
  ASSERT_EQ(r.t.size(), 3u);
  EXPECT_DOUBLE_EQ(r.t[1], 1e-3);
  EXPECT_DOUBLE_EQ(r.ddx_M[0], 12.5);
  EXPECT_DOUBLE_EQ(r.ddz_M[0], -0.25);
  EXPECT_DOUBLE_EQ(r.ddx_M[1], 0.5);
  EXPECT_DOUBLE_EQ(r.ddz_M[1], 5.0);
  // A D that is not an exponent is no number.
  EXPECT_THROW((void)read_text("t,ax,az\n0,1D,2\n0.001,1,2\n"), Error);
  EXPECT_THROW((void)read_text("t,ax,az\n0,1D+1x,2\n0.001,1,2\n"), Error);
}

TEST(RecordReader, MoreUnits) {
  const RecordColumns r = read_text("t [\xCE\xBCs],ax [mg],az [ft/s^2]\n0,1000,1\n1000000,500,2\n");
  ASSERT_EQ(r.t.size(), 2u);
  EXPECT_DOUBLE_EQ(r.t[1], 1.0);
  EXPECT_DOUBLE_EQ(r.ddx_M[0], 9.80665);
  EXPECT_DOUBLE_EQ(r.ddz_M[1], 2 * 0.3048);
  EXPECT_DOUBLE_EQ(read_text("t [\xC2\xB5s],ax_mg,az_mg\n0,1,2\n").ddz_M[0], 2 * 9.80665e-3);
  // m.s-2 and m\xC2\xB7s\xE2\x81\xBB\xC2\xB2 (a middle dot, a superscript minus two).
  EXPECT_DOUBLE_EQ(read_text("t,ax [m.s-2],az [m\xC2\xB7s\xE2\x81\xBB\xC2\xB2]\n0,1,2\n").ddz_M[0],
                   2.0);
}

// A logger's export: metadata lines before the header (no comment marks), a line of units under
// it. The preamble is skipped and the units read from that line, each said in a note; a header
// whose first data row holds text in a column not read, or a bad number, is still the header.
TEST(RecordReader, PreambleAndALineOfUnitsUnderTheHeader) {
  const RecordColumns r = read_text(
      "Device: HAMM HD+ 90 VO\nOperator: test\nSampling rate = 1000 Hz\n"
      "Time;Acc X;Acc Z\nms;g;[m/s^2]\n0;1;2\n1;-1;-2\n");
  ASSERT_EQ(r.t.size(), 2u);
  EXPECT_DOUBLE_EQ(r.t[1], 1e-3);
  EXPECT_DOUBLE_EQ(r.ddx_M[0], 9.80665);
  EXPECT_DOUBLE_EQ(r.ddz_M[1], -2.0);
  EXPECT_EQ(r.delimiter, "semicolon");
  int preamble = 0, units = 0;
  for (const std::string& n : r.notes) {
    preamble += n.find("skipped 3 lines before the header") != std::string::npos &&
                n.find("line 4") != std::string::npos;
    units += n.find("units from line 5, under the header") != std::string::npos;
  }
  EXPECT_EQ(preamble, 1);
  EXPECT_EQ(units, 1);
  // Headerless data after a preamble.
  RecordReading columns;
  columns.t_col = "1";
  columns.x_col = "2";
  columns.z_col = "3";
  const RecordColumns headless = read_text("Logger: X\n0,1,2\n1,3,4\n", columns);
  ASSERT_EQ(headless.t.size(), 2u);
  EXPECT_DOUBLE_EQ(headless.ddx_M[1], 3.0);
  // The first line stays the header when the data under it hold text or a bad number.
  EXPECT_EQ(read_text("t,ax,az,note\n0,1,2,start\n1,3,4,\n").t.size(), 2u);
  EXPECT_NE(message_of("t,ax,az\n0,1,2\n1,abc,2\n").find("record.csv:3: column 'ax'"),
            std::string::npos);
  EXPECT_NE(message_of("t,ax,az\n0,x1,2\n").find("record.csv:2: column 'ax'"), std::string::npos);
  // A whitespace-delimited preamble of "key value" pairs with numbers: two-cell lines with a
  // number look like a header and its data for a line or two, not for three; the header is the
  // line over three rows of its own width, with or without a header line.
  const std::string pairs = "Device HAMM-XYZ\nRate 1000\nGain 2.5\n";
  std::string rows;
  for (int i = 0; i < 4; ++i)
    rows += std::to_string(i) + " " + std::to_string(i % 2) + " " + std::to_string(2 * i) + "\n";
  const RecordColumns spaced = read_text(pairs + "t ax az\n" + rows);
  ASSERT_EQ(spaced.t.size(), 4u);
  EXPECT_DOUBLE_EQ(spaced.ddz_M[3], 6.0);
  EXPECT_EQ(spaced.delimiter, "whitespace");
  int skipped = 0;
  for (const std::string& n : spaced.notes)
    skipped += n.find("skipped 3 lines before the header") != std::string::npos;
  EXPECT_EQ(skipped, 1);
  const RecordColumns spaced_headless = read_text(pairs + rows, columns);
  ASSERT_EQ(spaced_headless.t.size(), 4u);
  EXPECT_DOUBLE_EQ(spaced_headless.ddx_M[1], 1.0);
  // Data rows with a trailing delimiter: still under the first line, whose columns they fill
  // (the delimiter at their end holds no value; it was a ragged-row error before).
  const RecordColumns trailing = read_text("t,ax,az\n0,1,2,\n1,3,4,\n");
  ASSERT_EQ(trailing.t.size(), 2u);
  EXPECT_DOUBLE_EQ(trailing.ddx_M[1], 3.0);
}

// An accelerometer reads +1 g at rest along an axis pointing up: a z column whose mean is about
// +1 g read as positive down points up. By default (auto) it is negated, with a note; an explicit
// direction is kept, with a note when the mean contradicts it.
TEST(RecordReader, GravityInTheZReadingDecidesItsAxis) {
  const std::string with_gravity = "t,acc_x [g],acc_z [g]\n0,0.1,1.05\n0.001,-0.1,0.95\n";
  const auto note_of = [](const RecordColumns& r, const std::string& what) {
    std::string found;
    for (const std::string& n : r.notes)
      if (n.find(what) != std::string::npos) found += n;
    return found;
  };
  const RecordColumns automatic = read_text(with_gravity);
  EXPECT_EQ(automatic.z_positive, "up");
  EXPECT_DOUBLE_EQ(automatic.z_factor, -kStandardGravity);
  EXPECT_DOUBLE_EQ(automatic.ddz_M[0], -1.05 * kStandardGravity);
  EXPECT_DOUBLE_EQ(automatic.ddz_M[1], -0.95 * kStandardGravity);
  EXPECT_DOUBLE_EQ(automatic.ddx_M[0], 0.1 * kStandardGravity);  // x as it was
  EXPECT_NE(note_of(automatic, "read as pointing up (negated)").find("give --z-positive down"),
            std::string::npos);
  EXPECT_NE(note_of(automatic, "z_M'': column 'acc_z [g]' x -9.80665 -> m/s^2"), "");

  RecordReading down;
  down.z_positive = "down";
  const RecordColumns kept = read_text(with_gravity, down);
  EXPECT_EQ(kept.z_positive, "down");
  EXPECT_DOUBLE_EQ(kept.ddz_M[0], 1.05 * kStandardGravity);
  EXPECT_NE(note_of(kept, "about +1 g").find("give --z-positive up or auto"), std::string::npos);

  RecordReading up;
  up.z_positive = "up";
  const RecordColumns read_up = read_text(with_gravity, up);  // read as up: -1 g, as it should be
  EXPECT_EQ(note_of(read_up, "about +1 g"), "");
  EXPECT_EQ(read_up.z_positive, "up");
  EXPECT_DOUBLE_EQ(read_up.ddz_M[0], -1.05 * kStandardGravity);

  // Without gravity the column says nothing: read as positive down.
  const RecordColumns plain = read_text("t,acc_x [g],acc_z [g]\n0,0.1,0.05\n0.001,-0.1,-0.05\n");
  EXPECT_EQ(note_of(plain, "about +1 g"), "");
  EXPECT_EQ(plain.z_positive, "down");
  EXPECT_TRUE(plain.z_open);  // nothing decided it: identify may (IdentifyOptions::z_open)
  EXPECT_FALSE(read_text("t,acc_x [g],acc_z [g]\n0,0.1,0.05\n0.001,-0.1,-0.05\n", down).z_open);
  EXPECT_DOUBLE_EQ(plain.ddz_M[0], 0.05 * kStandardGravity);
  // -1 g read as down: the downward axis an accelerometer at rest reads so; nothing changed.
  const RecordColumns downward =
      read_text("t,acc_x [g],acc_z [g]\n0,0.1,-1.05\n0.001,-0.1,-0.95\n");
  EXPECT_EQ(downward.z_positive, "down");
  EXPECT_FALSE(downward.z_open);   // gravity confirms it
  EXPECT_FALSE(automatic.z_open);  // gravity turned it
  EXPECT_EQ(note_of(downward, "about +1 g"), "");

  // Read as up, a mean of -1 g in the file: the axis points down after all.
  const RecordColumns wrong =
      read_text("t,acc_x [g],acc_z [g]\n0,0.1,-1.05\n0.001,-0.1,-0.95\n", up);
  EXPECT_NE(note_of(wrong, "about +1 g").find("give --z-positive down or auto"), std::string::npos);
  EXPECT_DOUBLE_EQ(wrong.ddz_M[0], 1.05 * kStandardGravity);  // kept as given

  // The notes in their order: t, x_M'', then z_M'' (its factor after gravity turned it), then
  // gravity's reason.
  ASSERT_EQ(automatic.notes.size(), 3u);
  EXPECT_EQ(automatic.notes[0].rfind("x_M'': column 'acc_x [g]'", 0), 0u);
  EXPECT_EQ(automatic.notes[1].rfind("z_M'': column 'acc_z [g]' x -9.80665", 0), 0u);
  EXPECT_EQ(automatic.notes[2].rfind("z_M'': read as pointing up", 0), 0u);
  const RecordColumns timed = read_text("t [ms],acc_x [g],acc_z [g]\n0,0.1,1.05\n1,-0.1,0.95\n");
  ASSERT_EQ(timed.notes.size(), 4u);
  EXPECT_EQ(timed.notes[0].rfind("t: column 't [ms]' x 0.001", 0), 0u);
  EXPECT_EQ(timed.notes[1].rfind("x_M'': column 'acc_x [g]'", 0), 0u);
  EXPECT_EQ(timed.notes[2].rfind("z_M'': column 'acc_z [g]' x -9.80665", 0), 0u);
  EXPECT_EQ(timed.notes[3].rfind("z_M'': read as pointing up", 0), 0u);
  // A z column named and written as the model's, read as it is: no note for it.
  const RecordColumns model = read_text("t,ddx_M,ddz_M\n0,1,-2\n0.001,-1,2\n");
  EXPECT_TRUE(model.notes.empty()) << model.notes.front();
}

// Accelerations without a unit are read in m/s^2, unless the vertical's mean of about +-1 says
// they are in g with gravity (both read in g, with a note); without gravity the unit stays open
// for identify (RecordColumns::units_open). A unit in the header, --units or the model's own
// names decide it.
TEST(RecordReader, GravityInGTellsTheUnitOfColumnsWithoutOne) {
  const RecordColumns in_g = read_text("t,ax,az\n0,0.5,1.05\n0.001,-0.5,0.95\n");
  EXPECT_DOUBLE_EQ(in_g.ddx_M[0], 0.5 * kStandardGravity);
  EXPECT_DOUBLE_EQ(in_g.ddz_M[0], -1.05 * kStandardGravity);  // and gravity turned z: up
  EXPECT_DOUBLE_EQ(in_g.x_factor, kStandardGravity);
  EXPECT_DOUBLE_EQ(in_g.z_factor, -kStandardGravity);
  EXPECT_EQ(in_g.z_positive, "up");
  EXPECT_FALSE(in_g.units_open);
  EXPECT_FALSE(in_g.z_open);
  bool said = false;
  for (const std::string& n : in_g.notes)
    said = said || n.rfind("accelerations: no unit in the header", 0) == 0;
  EXPECT_TRUE(said);
  // -1 g: in g, pointing down as read.
  const RecordColumns down = read_text("t,ax,az\n0,0.5,-1.05\n0.001,-0.5,-0.95\n");
  EXPECT_DOUBLE_EQ(down.ddz_M[0], -1.05 * kStandardGravity);
  EXPECT_EQ(down.z_positive, "down");
  // Gravity in m/s^2 (a mean of about -9.81 or +9.81): m/s^2 as read, the unit told, said so.
  for (const double g : {-9.81, 9.81}) {
    const RecordColumns si_g = read_text("t,ax,az\n0,0.5," + std::to_string(g + 0.3) +
                                         "\n0.001,-0.5," + std::to_string(g - 0.3) + "\n");
    EXPECT_DOUBLE_EQ(si_g.ddx_M[0], 0.5);
    EXPECT_NEAR(std::abs(si_g.ddz_M[0]), std::abs(g + 0.3), 1e-12);
    EXPECT_FALSE(si_g.units_open);
    EXPECT_TRUE(has_note(si_g, "is gravity in m/s^2"));
  }
  // No gravity: m/s^2, the unit open.
  const RecordColumns open = read_text("t,ax,az\n0,0.5,0.05\n0.001,-0.5,-0.05\n");
  EXPECT_DOUBLE_EQ(open.ddx_M[0], 0.5);
  EXPECT_TRUE(open.units_open);
  EXPECT_TRUE(open.z_open);
  // A unit given decides it, and a mean of 1 m/s^2 is then an offset.
  RecordReading si;
  si.units = "m/s2";
  const RecordColumns given = read_text("t,ax,az\n0,0.5,1.05\n0.001,-0.5,0.95\n", si);
  EXPECT_DOUBLE_EQ(given.ddz_M[0], 1.05);
  EXPECT_FALSE(given.units_open);
  EXPECT_FALSE(read_text("t,ax [m/s^2],az [m/s^2]\n0,0.5,1.05\n0.001,-0.5,0.95\n").units_open);
  EXPECT_FALSE(read_text("t,ddx_M,ddz_M\n0,0.5,1.05\n0.001,-0.5,0.95\n").units_open);
  EXPECT_DOUBLE_EQ(read_text("t,ddx_M,ddz_M\n0,0.5,1.05\n0.001,-0.5,0.95\n").ddz_M[0], 1.05);
}

// The rule read_record's z_positive "auto" and Python's identify() share: a mean within 0.15 g
// of +1 g, and nothing else, is gravity along an upward axis.
TEST(RecordReader, GravityPointsUpWithinItsBandOfOneG) {
  double mean = 0.0;
  EXPECT_TRUE(gravity_points_up({kStandardGravity + 1.0, kStandardGravity - 1.0}, &mean));
  EXPECT_DOUBLE_EQ(mean, kStandardGravity);
  const double edge = kGravityBand * kStandardGravity;
  EXPECT_TRUE(gravity_points_up({kStandardGravity + 0.99 * edge}));
  EXPECT_TRUE(gravity_points_up({kStandardGravity - 0.99 * edge}));
  EXPECT_FALSE(gravity_points_up({kStandardGravity + 1.01 * edge}));
  EXPECT_FALSE(gravity_points_up({kStandardGravity - 1.01 * edge}));
  EXPECT_FALSE(gravity_points_up({-kStandardGravity}));  // an axis pointing down
  EXPECT_FALSE(gravity_points_up({}, &mean));
  EXPECT_TRUE(std::isnan(mean));
}

// UTF-16 text with its byte-order mark (a spreadsheet's "Unicode text" export: tab separated,
// decimal commas in a German locale) is read as the UTF-8 text it encodes, a surrogate pair and
// a superscript two included; what is not text is named, not read as a header.
TEST(RecordReader, UTF16TextIsReadAndWhatIsNotTextIsNamed) {
  // "Zeit [ms]\tBeschl. X [m/s\u00B2]\tBeschl. Z [m/s\u00B2]\t\U0001F600\n0\t1,5\t-0,25\t1\n..."
  const std::u16string text =
      u"Zeit [ms]\tBeschl. X [m/s\u00B2]\tBeschl. Z [m/s\u00B2]\tnote \U0001F600\n"
      u"0\t1,5\t-0,25\t1\n1\t2,5\t0,75\t1\n";
  for (const bool little : {true, false}) {
    SCOPED_TRACE(little);
    std::string bytes = little ? "\xFF\xFE" : "\xFE\xFF";
    for (const char16_t u : text) {
      const char lo = static_cast<char>(u & 0xFF), hi = static_cast<char>(u >> 8);
      bytes += little ? std::string{lo, hi} : std::string{hi, lo};
    }
    const RecordColumns r = read_text(bytes);
    ASSERT_EQ(r.t.size(), 2u);
    EXPECT_DOUBLE_EQ(r.t[1], 1e-3);
    EXPECT_DOUBLE_EQ(r.ddx_M[0], 1.5);
    EXPECT_DOUBLE_EQ(r.ddz_M[1], 0.75);
    EXPECT_EQ(r.delimiter, "tab");
    EXPECT_EQ(r.x_column, "Beschl. X [m/s\xC2\xB2]");
    ASSERT_FALSE(r.notes.empty());
    EXPECT_EQ(r.notes.front(), std::string("read as UTF-16 text (") + (little ? "little" : "big") +
                                   "-endian, by its byte-order mark)");
  }
  // A lone surrogate is the replacement character U+FFFD (valid UTF-8 in the header): the
  // column "az" followed by an unpaired high surrogate.
  const RecordColumns lone =
      read_text(std::string("\xFF\xFEt\0,\0a\0x\0,\0a\0z\0\x00\xD8\n\0"
                            "0\0,\0\x31\0,\0\x32\0\n\0",
                            30));
  EXPECT_EQ(lone.z_column, "az\xEF\xBF\xBD");
  EXPECT_DOUBLE_EQ(lone.ddz_M[0], 2.0);
  // Tab separated UTF-8 with decimal commas, too.
  const RecordColumns tabbed = read_text("t\tax\taz\n0\t1,5\t2\n0,001\t-1\t0,5\n");
  EXPECT_DOUBLE_EQ(tabbed.t[1], 0.001);
  EXPECT_DOUBLE_EQ(tabbed.ddx_M[0], 1.5);
  for (const auto& [bytes, what] : std::vector<std::pair<std::string, std::string>>{
           {std::string("\x1F\x8B\x08\x08garbage\n", 12), "a gzip-compressed file"},
           {"PK\x03\x04garbage\n", "a zip archive (an Excel .xlsx workbook is one)"},
           {"\xD0\xCF\x11\xE0garbage\n", "an Excel .xls workbook"},
           {"\x89HDF\r\n", "an HDF5 file"},
           {std::string("t\0,\0a\0x\n", 9), "not text (a NUL byte in its first line"},
           {"\xFFgarbage\n", "not text (its first byte is 0xFF"}}) {
    SCOPED_TRACE(what);
    EXPECT_EQ(message_of(bytes).find("record.csv: " + what), 0u) << message_of(bytes);
  }
}

// A two-dimensional record (another implementation's x and y, no z): its y acceleration is the
// vertical, read as pointing up (the usual Cartesian y) unless its mean of -1 g says it points
// down; beside a z column, y is a three-axis logger's lateral channel.
TEST(RecordReader, ATwoDimensionalRecordsYIsTheVertical) {
  const auto has = has_note;
  for (const std::string header : {"t,ax,ay", "time,acc_x,acc_y", "t,x'',y''", "t,ddx,ddy"}) {
    SCOPED_TRACE(header);
    const RecordColumns r = read_text(header + "\n0,0.5,-0.25\n0.001,1.5,0.75\n");
    EXPECT_DOUBLE_EQ(r.ddx_M[0], 0.5);
    EXPECT_DOUBLE_EQ(r.ddz_M[1], -0.75);  // y up: negated
    EXPECT_EQ(r.z_positive, "up");
    EXPECT_TRUE(
        has(r, "is read as the vertical (a two-dimensional record's x and y), pointing up"));
  }
  RecordReading down;
  down.z_positive = "down";
  const RecordColumns as_down = read_text("t,ax,ay\n0,0.5,-0.25\n0.001,1.5,0.75\n", down);
  EXPECT_DOUBLE_EQ(as_down.ddz_M[1], 0.75);
  EXPECT_EQ(as_down.z_positive, "down");
  // Gravity kept along an upward y (+1 g): up, as guessed; along a downward y (-1 g): turned.
  const RecordColumns up_g = read_text("t,ax [g],ay [g]\n0,0.5,1.25\n0.001,1.5,0.75\n");
  EXPECT_EQ(up_g.z_positive, "up");
  EXPECT_FALSE(has(up_g, "about +1 g"));
  const RecordColumns down_g = read_text("t,ax [g],ay [g]\n0,0.5,-1.25\n0.001,1.5,-0.75\n");
  EXPECT_EQ(down_g.z_positive, "down");
  EXPECT_DOUBLE_EQ(down_g.ddz_M[0], -1.25 * kStandardGravity);
  EXPECT_TRUE(has(down_g, "read as pointing down (as it is)"));
  // Three axes: z is the vertical, y the lateral channel.
  const RecordColumns three = read_text("t,ax,ay,az\n0,0.5,0.2,-0.25\n0.001,1.5,-0.1,0.75\n");
  EXPECT_EQ(three.z_column, "az");
  EXPECT_DOUBLE_EQ(three.ddz_M[1], 0.75);
  EXPECT_EQ(three.z_positive, "down");
  EXPECT_FALSE(has(three, "two-dimensional"));
  EXPECT_FALSE(has(three, "is read as the vertical"));
  // With gravity in z (and y lateral, about 0), z stays the vertical.
  const RecordColumns z_g = read_text("t,ax,ay,az\n0,0.5,0.2,-9.5\n0.001,1.5,-0.1,-10.1\n");
  EXPECT_EQ(z_g.z_column, "az");
  EXPECT_FALSE(has(z_g, "is read as the vertical"));
}

// A three-axis logger mounted with its y axis vertical: gravity (+-1 g at rest) is in the mean of
// y, not of z (now a horizontal axis, about 0): y is read as the vertical, with a note naming
// the flag that reads z; its direction from gravity's sign as for any vertical column. In g
// without a unit (a mean of about +-1), both channels in g. Where z has gravity too, or y has
// none, or --z-col chooses, nothing changes. A z that never changes beside a y that does (three
// coordinates of a model, z along the axle) makes y the vertical too.
TEST(RecordReader, AThreeAxisLoggersYWithGravityIsTheVertical) {
  const auto has = has_note;
  // m/s^2 in the header; y points down (mean -9.81: read as it is).
  const std::string si =
      "t,acc_x [m/s^2],acc_y [m/s^2],acc_z [m/s^2]\n0,0.5,-9.3,0.2\n0.001,1.5,-10.3,-0.1\n";
  const RecordColumns down = read_text(si);
  EXPECT_EQ(down.z_column, "acc_y [m/s^2]");
  EXPECT_DOUBLE_EQ(down.ddz_M[0], -9.3);
  EXPECT_DOUBLE_EQ(down.ddx_M[1], 1.5);
  EXPECT_EQ(down.z_positive, "down");
  EXPECT_TRUE(has(down, "the y column 'acc_y [m/s^2]' is read as the vertical"));
  EXPECT_TRUE(has(down, "give --z-col 'acc_z [m/s^2]' to read z"));
  // In g, y pointing up (mean +1 g): turned round by gravity's rule.
  const RecordColumns up = read_text("t,ax [g],ay [g],az [g]\n0,0.5,0.95,0.02\n0.001,1.5,1.05,0\n");
  EXPECT_EQ(up.z_column, "ay [g]");
  EXPECT_EQ(up.z_positive, "up");
  EXPECT_DOUBLE_EQ(up.ddz_M[0], -0.95 * kStandardGravity);
  EXPECT_DOUBLE_EQ(up.z_factor, -kStandardGravity);
  // Without units: y's mean about 1 is gravity in g; both read in g.
  const RecordColumns g = read_text("t,ax,ay,az\n0,0.5,0.95,0.02\n0.001,1.5,1.05,0\n");
  EXPECT_EQ(g.z_column, "ay");
  EXPECT_DOUBLE_EQ(g.ddx_M[0], 0.5 * kStandardGravity);
  EXPECT_EQ(g.z_positive, "up");
  EXPECT_FALSE(g.units_open);
  // Gravity in both (a logger tilted so) or in neither: z stays the vertical.
  EXPECT_EQ(read_text("t,ax,ay,az\n0,0.5,-9.3,9.7\n0.001,1.5,-10.3,9.9\n").z_column, "az");
  EXPECT_EQ(read_text("t,ax,ay,az\n0,0.5,0.3,0.2\n0.001,1.5,-0.3,-0.1\n").z_column, "az");
  // A y cell without a number (z's and x's fine): y is not taken, the row is kept.
  const RecordColumns gap = read_text(si + "0.002,1,,0.3\n");
  EXPECT_EQ(gap.z_column, "acc_z [m/s^2]");
  EXPECT_EQ(gap.t.size(), 3u);
  // --z-col chooses z; --units given: the columns are read as told.
  RecordReading named;
  named.z_col = "acc_z [m/s^2]";
  EXPECT_EQ(read_text(si, named).z_column, "acc_z [m/s^2]");
  // Another implementation's three coordinates, y vertical and z along the axle (the same value
  // in every row), no gravity: y is the vertical, pointing up as a two-dimensional record's y.
  const std::string coordinates = "t,ax,ay,az\n0,0.5,-0.25,0\n0.001,1.5,0.75,0\n";
  const RecordColumns model = read_text(coordinates);
  EXPECT_EQ(model.z_column, "ay");
  EXPECT_EQ(model.z_positive, "up");
  EXPECT_DOUBLE_EQ(model.ddz_M[1], -0.75);
  EXPECT_TRUE(model.z_open);  // no gravity: identify may still fit it negated
  // A logger's bare X, Y, Z (Time,X,Y,Z) follow the same rules: Y with gravity is the vertical
  // (Z, lateral, was read as the vertical without a word).
  const RecordColumns bare = read_text("Time,X,Y,Z\n0,0.5,9.3,0.02\n0.001,1.5,10.3,-0.01\n");
  EXPECT_EQ(bare.z_column, "Y");
  EXPECT_EQ(bare.z_positive, "up");
  EXPECT_TRUE(has(bare, "the y column 'Y' is read as the vertical"));
  EXPECT_TRUE(has(model, "'az' has the same value in every row"));
  EXPECT_FALSE(has(model, "the same value (0 m/s^2) in every row"));  // not a dead vertical
  RecordReading as_down;
  as_down.z_positive = "down";
  const RecordColumns model_down = read_text(coordinates, as_down);
  EXPECT_DOUBLE_EQ(model_down.ddz_M[1], 0.75);
  EXPECT_TRUE(has(model_down, "pointing down (--z-positive)"));
  // Both still: z stays (and is said to be dead).
  EXPECT_EQ(read_text("t,ax,ay,az\n0,0.5,0,0\n0.001,1.5,0,0\n").z_column, "az");
}

// A channel with the same value in every row (a dead sensor) is said, with its value in m/s^2;
// one that changes, or a record of one row, says nothing.
TEST(RecordReader, AConstantChannelIsSaid) {
  const auto dead = [](const RecordColumns& r, const std::string& channel) {
    int found = 0;
    for (const std::string& n : r.notes)
      found += n.rfind(channel + ": the same value", 0) == 0 &&
               n.find("dead or disconnected") != std::string::npos;
    return found;
  };
  const RecordColumns z_dead = read_text("t,acc_x [g],acc_z [g]\n0,0.1,-1\n0.001,-0.1,-1\n");
  EXPECT_EQ(dead(z_dead, "z_M''"), 1);
  EXPECT_EQ(dead(z_dead, "x_M''"), 0);
  for (const std::string& n : z_dead.notes) {
    if (n.rfind("z_M'': the same", 0) == 0) {
      EXPECT_NE(n.find("(-9.80665 m/s^2)"), std::string::npos) << n;
    }
  }
  const RecordColumns x_dead = read_text("t,ddx_M,ddz_M\n0,0,1\n0.001,0,2\n0.002,0,1\n");
  EXPECT_EQ(dead(x_dead, "x_M''"), 1);
  EXPECT_EQ(dead(x_dead, "z_M''"), 0);
  EXPECT_EQ(dead(read_text("t,ddx_M,ddz_M\n0,1,2\n0.001,2,1\n"), "x_M''"), 0);
  EXPECT_EQ(dead(read_text("t,ddx_M,ddz_M\n0,1,2\n"), "x_M''"), 0);
}

TEST(RecordReader, SemicolonsWithDecimalCommas) {
  const RecordColumns r = read_text("t[s];ddx_M[m/s^2];ddz_M[m/s^2]\n0,5;1,25;-2\n");
  EXPECT_EQ(r.delimiter, "semicolon");
  EXPECT_DOUBLE_EQ(r.t[0], 0.5);
  EXPECT_DOUBLE_EQ(r.ddx_M[0], 1.25);
  EXPECT_DOUBLE_EQ(r.ddz_M[0], -2.0);
  EXPECT_TRUE(r.notes.empty());  // read as the model writes it
}

// Both sides of a switch at its time, as an event-driven integrator writes them: each run of
// rows with one time is one sample, the accelerations averaged, the position its first row's;
// the analysis then accepts the record (it needs increasing times, and says so for arrays).
// A clock rounded to a tick about as long as the sampling step: an 800 samples/s logger whose
// stamps are whole milliseconds, floored (steps of 1, 1, 1 and 2 ms), and a 1024 samples/s one
// (steps of 1 ms and repeated stamps). Taken as the sampling times, such stamps gave G about 1 %
// off in every window with no word; the note says so and names --rate. A 1 kHz logger stamping
// whole milliseconds (every step one tick) is exact, and says nothing.
TEST(RecordReader, AClockRoundedToItsTickIsSaid) {
  const auto record = [](double rate) {
    std::string text = "t [ms],ax,az\n";
    for (int i = 0; i < 400; ++i)
      text += std::to_string(static_cast<long>(std::floor(i * 1000.0 / rate + 1e-9))) + "," +
              std::to_string(std::sin(0.3 * i)) + ",1\n";
    return text;
  };
  const auto rounded = [](const RecordColumns& r) {
    return std::any_of(r.notes.begin(), r.notes.end(), [](const std::string& n) {
      return n.find("a clock rounded to its tick") != std::string::npos &&
             n.find("--rate HZ") != std::string::npos;
    });
  };
  EXPECT_TRUE(rounded(read_text(record(800.0))));
  const RecordColumns r1024 = read_text(record(1024.0));
  EXPECT_TRUE(rounded(r1024)) << ::testing::PrintToString(r1024.notes);
  EXPECT_FALSE(rounded(read_text(record(1000.0))));
  EXPECT_FALSE(rounded(read_text(record(500.0))));
}

TEST(RecordReader, RowsAtTheTimeOfTheRowBeforeAreOneSample) {
  const RecordColumns r = read_text(
      "t,ax,az,x\n0,1,2,5\n0.001,1,2,6\n0.001,3,-2,7\n0.001,5,0,8\n0.002,1,2,9\n0.003,4,4,9\n"
      "0.003,2,2,9\n");
  EXPECT_EQ(r.t, (std::vector<double>{0, 0.001, 0.002, 0.003}));
  EXPECT_EQ(r.ddx_M, (std::vector<double>{1, 3, 1, 3}));
  EXPECT_EQ(r.ddz_M, (std::vector<double>{2, 0, 2, 3}));
  EXPECT_TRUE(std::any_of(r.notes.begin(), r.notes.end(), [](const std::string& n) {
    return n.find("3 rows repeat the time of the row before (the first at t = 0.001 s") !=
           std::string::npos;
  })) << ::testing::PrintToString(r.notes);
  // One repeat in a hundred rows: an integrator's switch; every other row a repeat: a clock
  // coarser than the sampling (2 kHz stamped to the millisecond), and the note names --rate.
  const auto note_of = [](const std::string& text) {
    std::string all;
    for (const std::string& n : read_text(text).notes) all += n;
    return all;
  };
  std::string one = "t,ax,az\n", pairs = one;
  for (int i = 0; i < 100; ++i) {
    one += std::to_string(i == 50 ? 49 : i) + "e-3,1,2\n";
    pairs += std::to_string(i / 2) + "e-3,1,2\n";
  }
  EXPECT_NE(note_of(one).find("an event-driven integrator"), std::string::npos);
  EXPECT_EQ(note_of(one).find("--rate"), std::string::npos);
  EXPECT_NE(note_of(pairs).find("coarser than the sampling"), std::string::npos);
  EXPECT_NE(note_of(pairs).find("--rate HZ"), std::string::npos);
  // Every stamp holding two rows: the clock, its rows spread to the next stamp (averaged, each
  // pair was one sample a quarter of a millisecond late), the last by the median step.
  const RecordColumns spread = read_text(pairs);
  ASSERT_EQ(spread.t.size(), 100u);
  for (std::size_t i = 0; i < 100; ++i)
    EXPECT_NEAR(spread.t[i], 0.5e-3 * static_cast<double>(i), 1e-15) << i;
  // The same in whole milliseconds without a unit (a logger's epoch ms): read in ms, as a clock
  // without repeats is (the median step of all rows was 0, and the column was read in s: 2
  // samples/s).
  std::string epoch_ms = "timestamp,ax,az\n";
  for (int i = 0; i < 100; ++i) epoch_ms += std::to_string(1700000000123LL + i / 2) + ",1,2\n";
  const RecordColumns ms = read_text(epoch_ms);
  ASSERT_EQ(ms.t.size(), 100u);
  EXPECT_EQ(ms.t_factor, 1e-3);
  EXPECT_NEAR(ms.t[99] - ms.t[0], 99 * 0.5e-3, 4e-7);  // a double's step at 1.7e9 s: 2.4e-7
  EXPECT_NE(note_of(epoch_ms).find("read in ms (2000 samples/s)"), std::string::npos)
      << note_of(epoch_ms);
  // Stamps with irregular repeats (a third of them): averaged, as switches are. Every other step
  // one tick of 1 ms: a clock rounded to its tick, as the note says; with steps of 0.7 ms and
  // more, the clock only may be coarser than the sampling.
  std::string some = "t,ax,az\n", finer = some;
  for (int i = 0; i < 99; ++i) {
    some += std::to_string(i) + "e-3,1,2\n" + (i % 3 == 0 ? std::to_string(i) + "e-3,1,2\n" : "");
    const std::string t = std::to_string(0.7e-3 * i + (i % 2) * 0.13e-3);
    finer += t + ",1,2\n" + (i % 3 == 0 ? t + ",1,2\n" : "");
  }
  EXPECT_EQ(read_text(some).t.size(), 99u);
  EXPECT_NE(note_of(some).find("a clock rounded to its tick"), std::string::npos);
  EXPECT_NE(note_of(finer).find("may be coarser than the sampling"), std::string::npos);
  RecordReading o;
  o.pos_col = "x";
  EXPECT_EQ(read_text("t,ax,az,x\n0,1,2,5\n0.001,1,2,6\n0.001,3,-2,7\n", o).position,
            (std::vector<double>{5, 6}));
  const std::vector<double> t = {0, 0.001, 0.001}, a = {1, 2, 3};
  try {
    analyze_windows(t, a, a, {});
    ADD_FAILURE() << "a repeated time accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("as the CSV reader does"), std::string::npos) << e.what();
  }
}

// Messages name the record, the line and the column, or the option to give.
TEST(RecordReader, MessagesNameTheLineColumnOrOption) {
  EXPECT_NE(message_of("t,ax,az\n0,1,2\n0.001,1,oops\n")
                .find("record.csv:3: column 'az' must be a number; got 'oops'"),
            std::string::npos);
  EXPECT_NE(message_of("a,b,c\n0,1,2\n").find("no column looks like the time"), std::string::npos);
  // Without a time column: the rate is the other way.
  EXPECT_NE(message_of("acc_x,acc_z\n1,2\n").find("or give the sampling rate with --rate HZ"),
            std::string::npos);
  EXPECT_EQ(message_of("t,a,b\n0,1,2\n").find("--rate"), std::string::npos);
  EXPECT_NE(message_of("t,ax,az\n0,1\n").find("record.csv:2: 2 cells, but the header has 3"),
            std::string::npos);
  EXPECT_NE(message_of("# only comments\n").find("no data"), std::string::npos);
  EXPECT_NE(message_of("0,1,2\n").find("has no header line: give the time column"),
            std::string::npos);
}

// One column read as two quantities, two columns of one name, a time that never advances: each
// was read without a word (the same column as x and z gave area 0 and "quality ok").
TEST(RecordReader, AColumnReadTwiceOrNamedTwiceIsRefused) {
  const std::string rows = "t,ddx_M,ddz_M\n0,1,2\n0.001,3,4\n0.002,5,6\n";
  RecordReading o;
  o.x_col = "3";
  o.z_col = "ddz_M";
  EXPECT_NE(message_of(rows, o).find("--x-col and --z-col are the same column 'ddz_M' (column 3)"),
            std::string::npos)
      << message_of(rows, o);
  o = {};
  o.x_col = "t";
  EXPECT_NE(message_of(rows, o).find("--t-col and --x-col are the same column 't'"),
            std::string::npos);
  const std::string twice = "t,ddx_M,ddz_M,ddx_M\n0,1,2,10\n0.001,3,4,30\n";
  EXPECT_NE(message_of(twice).find("the header names several columns 'ddx_M' (columns 2, 4)"),
            std::string::npos)
      << message_of(twice);
  o = {};
  o.x_col = "ddx_M";
  EXPECT_NE(message_of(twice, o).find("several columns 'ddx_M'"), std::string::npos);
  o.x_col = "4";
  EXPECT_DOUBLE_EQ(read_text(twice, o).ddx_M[1], 30.0);
  EXPECT_NE(message_of("t,ax,az\n0,1,2\n0,3,4\n0,5,6\n")
                .find("the time column holds one time for all 3 rows (t = 0 s)"),
            std::string::npos)
      << message_of("t,ax,az\n0,1,2\n0,3,4\n0,5,6\n");
}

// A record with y and z accelerations and no x (a two-axis sensor's y and z channels, y along the
// direction of travel): y is the horizontal, with a note; beside an x column it is not.
TEST(RecordReader, YBesideZWithoutXIsTheHorizontal) {
  const std::string yz = "time,ay,az\n0,0.5,-0.2\n0.001,1.5,0.3\n";
  const RecordColumns r = read_text(yz);
  EXPECT_EQ(r.x_column, "ay");
  EXPECT_EQ(r.z_column, "az");
  EXPECT_DOUBLE_EQ(r.ddx_M[1], 1.5);
  EXPECT_DOUBLE_EQ(r.ddz_M[1], 0.3);
  EXPECT_TRUE(has_note(r, "no x column: the y column 'ay' is read as the horizontal"));
  RecordReading backward;
  backward.x_positive = "backward";
  const RecordColumns b = read_text(yz, backward);
  EXPECT_DOUBLE_EQ(b.ddx_M[1], -1.5);
  EXPECT_TRUE(has_note(b, "pointing backward (--x-positive)"));
  // --z-col naming z: y is still the horizontal; naming y: no horizontal is found.
  RecordReading z_named;
  z_named.z_col = "az";
  EXPECT_EQ(read_text(yz, z_named).x_column, "ay");
  RecordReading y_named;
  y_named.z_col = "ay";
  EXPECT_THROW(read_text(yz, y_named), Error);
  // Beside an x column, y is a three-axis logger's lateral channel.
  const RecordColumns xyz = read_text("t,ax,ay,az\n0,0.5,0.01,-0.2\n0.001,1.5,-0.01,0.3\n");
  EXPECT_EQ(xyz.x_column, "ax");
  EXPECT_EQ(xyz.z_column, "az");
}

// A three-axis logger mounted with x vertical: gravity in x's mean alone makes x the vertical
// (its direction by gravity, as any vertical's), and the one of y and z that moves more the
// horizontal (the other is along the axle), with a note; gravity in another column too, or
// --x-col, leaves the columns as named.
TEST(RecordReader, AThreeAxisLoggersXWithGravityIsTheVertical) {
  // In g, x pointing up (mean +1 g), y the direction of travel, z the axle's.
  const RecordColumns up =
      read_text("t,ax [g],ay [g],az [g]\n0,0.95,0.5,0.02\n0.001,1.05,-1.5,0.01\n");
  EXPECT_EQ(up.z_column, "ax [g]");
  EXPECT_EQ(up.x_column, "ay [g]");
  EXPECT_EQ(up.z_positive, "up");
  EXPECT_DOUBLE_EQ(up.ddz_M[0], -0.95 * kStandardGravity);
  EXPECT_DOUBLE_EQ(up.ddx_M[1], -1.5 * kStandardGravity);
  EXPECT_DOUBLE_EQ(up.x_factor, kStandardGravity);
  EXPECT_FALSE(up.units_open);
  EXPECT_TRUE(has_note(up, "the x column 'ax [g]' is read as the vertical"));
  EXPECT_TRUE(has_note(up, "'az [g]' along the axle"));
  // Without a unit, in m/s^2 (mean about -9.81): x the vertical, read in m/s^2.
  const RecordColumns si = read_text("t,ax,ay,az\n0,-9.3,0.5,0.02\n0.001,-10.3,-1.5,0.01\n");
  EXPECT_EQ(si.z_column, "ax");
  EXPECT_DOUBLE_EQ(si.ddz_M[1], -10.3);
  EXPECT_FALSE(si.units_open);
  // Without a unit, a mean of about 1 may be gravity in g or an offset of 1 m/s^2 (a slope): the
  // columns as named.
  EXPECT_EQ(read_text("t,ax,ay,az\n0,0.95,0.5,0.02\n0.001,1.05,-1.5,0.01\n").z_column, "az");
  // In m/s^2, x pointing down (mean -9.81: read as it is), z moving more than y: z the horizontal.
  const RecordColumns down =
      read_text("t,acc_x [m/s^2],acc_y [m/s^2],acc_z [m/s^2]\n0,-9.3,0.1,2\n0.001,-10.3,0.2,-3\n");
  EXPECT_EQ(down.z_column, "acc_x [m/s^2]");
  EXPECT_EQ(down.x_column, "acc_z [m/s^2]");
  EXPECT_EQ(down.z_positive, "down");
  EXPECT_DOUBLE_EQ(down.ddz_M[1], -10.3);
  EXPECT_DOUBLE_EQ(down.ddx_M[1], -3.0);
  RecordReading backward;
  backward.x_positive = "backward";
  EXPECT_DOUBLE_EQ(
      read_text("t,ax,ay,az\n0,-9.3,0.5,0.02\n0.001,-10.3,-1.5,0.01\n", backward).ddx_M[1], 1.5);
  // Gravity in x and in z (a tilted logger), or in none: the columns as named.
  EXPECT_EQ(read_text("t,ax,ay,az\n0,-9.3,0.5,-9.5\n0.001,-10.3,-1.5,-10.1\n").z_column, "az");
  EXPECT_EQ(read_text("t,ax,ay,az\n0,0.3,0.5,0.02\n0.001,-0.3,-1.5,0.01\n").z_column, "az");
  // --x-col given: read as told.
  RecordReading named;
  named.x_col = "ax";
  EXPECT_EQ(read_text("t,ax,ay,az\n0,-9.3,0.5,0.02\n0.001,-10.3,-1.5,0.01\n", named).z_column,
            "az");
}

// A record without a time column whose preamble (or a comment before the data) states the
// sampling rate: t from the row number at that rate, with a note naming the line. A frequency
// alone may be the excitation's and is not read; a time column, or --rate, goes first.
TEST(RecordReader, ARateStatedBeforeTheDataGivesTheTimes) {
  const std::string data = "ax,az\n1,2\n3,4\n5,6\n";
  for (const auto& [preamble, hz] :
       std::vector<std::pair<std::string, double>>{{"Sample rate: 1000 Hz", 1000.0},
                                                   {"# Sampling frequency [Hz] = 2000", 2000.0},
                                                   {"Sample interval: 2 ms", 500.0},
                                                   {"Abtastrate: 1 kHz", 1000.0},
                                                   {"rate = 250", 250.0},
                                                   {"% fs 4000", 4000.0}}) {
    SCOPED_TRACE(preamble);
    const RecordColumns r = read_text("Device: logger 7\n" + preamble + "\n" + data);
    ASSERT_EQ(r.t.size(), 3u);
    EXPECT_DOUBLE_EQ(r.t[2], 2.0 / hz);
    EXPECT_DOUBLE_EQ(r.ddz_M[1], 4.0);
    EXPECT_TRUE(has_note(r, "the sampling rate the record states at line 2"));
  }
  // An excitation frequency, or a rate out of [1, 1e7] Hz, is not a sampling rate.
  for (const std::string preamble : {"Frequency: 39 Hz", "Sample rate: 0.5 Hz", "rate = 1e9"}) {
    SCOPED_TRACE(preamble);
    EXPECT_THROW(read_text(preamble + "\n" + data), Error);
  }
  // --rate overrides the stated rate; a time column goes before it.
  RecordReading given;
  given.rate = 100.0;
  EXPECT_DOUBLE_EQ(read_text("Sample rate: 1000 Hz\n" + data, given).t[1], 0.01);
  const RecordColumns timed =
      read_text("Sample rate: 1000 Hz\nt,ax,az\n0,1,2\n0.004,3,4\n0.008,5,6\n");
  EXPECT_DOUBLE_EQ(timed.t[1], 0.004);
  EXPECT_FALSE(has_note(timed, "states at line"));
}

// A spreadsheet's export: a delimiter at the end of the data rows but not of the header, or of
// the header but not of the rows, holds no column; a time zone in the time column's brackets is
// not its unit.
TEST(RecordReader, TrailingDelimitersAndATimeZoneInTheHeader) {
  const RecordColumns rows = read_text("t,ax,az\n0,1,2,\n0.001,3,4,\n");
  ASSERT_EQ(rows.t.size(), 2u);
  EXPECT_DOUBLE_EQ(rows.ddz_M[1], 4.0);
  const RecordColumns head = read_text("t;ax;az;\n0;1;2\n0,001;3;4\n");
  ASSERT_EQ(head.t.size(), 2u);
  EXPECT_DOUBLE_EQ(head.t[1], 0.001);
  // A value beyond the header's columns is still an error.
  EXPECT_THROW(read_text("t,ax,az\n0,1,2,5\n0.001,3,4,6\n"), Error);
  const RecordColumns zone = read_text("Timestamp (UTC),ax,az\n0,1,2\n0.001,3,4\n");
  EXPECT_DOUBLE_EQ(zone.t[1], 0.001);
  EXPECT_THROW(read_text("Timestamp (days),ax,az\n0,1,2\n0.001,3,4\n"), Error);
}

}  // namespace
}  // namespace oscidrum

namespace oscidrum {
namespace {

// A time that goes back (a logger that restarted its clock, files joined) is refused at its line,
// with the file's name; the analysis named only the sample, without the file.
TEST(RecordReader, ATimeThatGoesBackIsNamedAtItsLine) {
  const std::string m = message_of("t,ddx_M,ddz_M\n0,1,2\n0.001,1,2\n0.002,1,2\n0,1,2\n");
  EXPECT_NE(m.find("record.csv:5: the time goes back: 0 s after 0.002 s"), std::string::npos) << m;
  // In seconds, from a column in ms (the message said "1.499 (in the time column's unit)" of a
  // column holding 1499).
  const std::string ms = message_of("Time [ms],ddx_M,ddz_M\n0,1,2\n1,1,2\n1499,1,2\n0,1,2\n");
  EXPECT_NE(ms.find("record.csv:5: the time goes back: 0 s after 1.499 s (the time column read in "
                    "seconds"),
            std::string::npos)
      << ms;
}

}  // namespace
}  // namespace oscidrum
