// core/json.h: the strict reader (what RFC 8259 forbids, plus duplicate keys
// and deep nesting, each refused with its line and column), the writer
// (member order kept, numbers that read back bit for bit), jsonLocation, and
// JsonReader's messages naming the JSON path of a bad value.
#include <QtTest>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/json.h"

using hs::Json;

namespace {

std::string refusal(const std::string& text) {
  std::string error;
  if (hs::parseJson(text, error)) return "(accepted)";
  return error;
}

// Hex of a double's bits, so a failed comparison shows what differs.
QByteArray bits(double d) {
  uint64_t u;
  std::memcpy(&u, &d, sizeof u);
  return QByteArray::number(qulonglong(u), 16);
}

}  // namespace

class TestCoreJson : public QObject {
  Q_OBJECT

 private slots:
  // Each case: the text, the place the error must name (counted by hand:
  // lines and columns from 1), and a word the message must hold.
  void refusedWithItsPlace_data() {
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<QString>("place");
    QTest::addColumn<QString>("word");
    // Numbers RFC 8259 does not allow. The place is the character where
    // the text stopped being JSON.
    QTest::newRow("1.") << QByteArray("[1.]") << "line 1, column 4" << "number";
    QTest::newRow("1.e5") << QByteArray("[1.e5]") << "line 1, column 4" << "number";
    QTest::newRow("leading zero") << QByteArray("[01]") << "line 1, column 3" << "";
    QTest::newRow("plus sign") << QByteArray("[+1]") << "line 1, column 2" << "";
    QTest::newRow(".5") << QByteArray("[.5]") << "line 1, column 2" << "";
    QTest::newRow("hex") << QByteArray("[0x10]") << "line 1, column 3" << "";
    QTest::newRow("NaN") << QByteArray("{\"a\": NaN}") << "line 1, column 7" << "";
    QTest::newRow("Infinity") << QByteArray("[Infinity]") << "line 1, column 2" << "";
    QTest::newRow("-Infinity") << QByteArray("[-Infinity]") << "line 1, column 3" << "";
    // A number past the range of a double: nlohmann names no place, the
    // reader finds the token.
    QTest::newRow("1e400") << QByteArray("{\"a\": [0,\n  1e400]}") << "line 2, column 3" << "range of a double";
    QTest::newRow("-1e400") << QByteArray("[-1e400]") << "line 1, column 2" << "range of a double";
    // Lone surrogates would become invalid UTF-8.
    QTest::newRow("lone high surrogate") << QByteArray(R"(["\ud800"])") << "line 1, column 9" << "surrogate";
    QTest::newRow("lone low surrogate") << QByteArray(R"(["\udc00"])") << "line 1, column 8" << "surrogate";
    QTest::newRow("high then not low") << QByteArray(R"(["\ud800\u0041"])") << "line 1, column 14" << "surrogate";
    // Duplicate keys: the place is the second one, however it is spelled.
    QTest::newRow("duplicate key") << QByteArray("{\"a\": 1, \"a\": 2}") << "line 1, column 10" << "duplicate key";
    QTest::newRow("duplicate key escaped") << QByteArray("{\"a\": 1,\n \"\\u0061\": 2}") << "line 2, column 2"
                                           << "duplicate key \"a\"";
    QTest::newRow("duplicate key nested") << QByteArray("{\"x\": {\"a\": 1}, \"y\": [{\"b\": 1, \"b\": 2}]}")
                                          << "line 1, column 32" << "duplicate key \"b\" in y[0]";
    // Trailing commas, comments, other syntax.
    QTest::newRow("trailing comma array") << QByteArray("[1,]") << "line 1, column 4" << "";
    QTest::newRow("trailing comma object") << QByteArray("{\"a\": 1,}") << "line 1, column 9" << "";
    QTest::newRow("comment") << QByteArray("[1] // note") << "line 1, column 5" << "";
    QTest::newRow("single quotes") << QByteArray("['a']") << "line 1, column 2" << "";
    QTest::newRow("garbage after") << QByteArray("[1]x") << "line 1, column 4" << "";
    QTest::newRow("missing colon") << QByteArray("{\"a\" 1}") << "line 1, column 6" << "";
    QTest::newRow("missing comma") << QByteArray("[1 2]") << "line 1, column 4" << "";
    QTest::newRow("bare leading zero") << QByteArray("01") << "line 1, column 2" << "";
    QTest::newRow("tru") << QByteArray("tru") << "line 1, column 4" << "";
    QTest::newRow("empty") << QByteArray("") << "line 1, column 1" << "";
    QTest::newRow("unterminated") << QByteArray("{\"a\": \"abc") << "line 1, column 11" << "";
    QTest::newRow("raw newline in string") << QByteArray("[\"a\nb\"]") << "line 1, column 4" << "";
    QTest::newRow("columns count characters") << QByteArray("[\"\xc3\xa9\", 1.]") << "line 1, column 9" << "";
    QTest::newRow("second line") << QByteArray("{\"a\": 1,\n \"b\": [1,,2]}") << "line 2, column 10" << "";
    QTest::newRow("invalid UTF-8") << QByteArray("[\"a\xff\"]") << "line 1, column 4" << "UTF-8";
  }
  void refusedWithItsPlace() {
    QFETCH(QByteArray, text);
    QFETCH(QString, place);
    QFETCH(QString, word);
    const std::string e = refusal(text.toStdString());
    QVERIFY2(e.rfind(place.toStdString() + ":", 0) == 0, e.c_str());
    QVERIFY2(e.find(word.toStdString()) != std::string::npos, e.c_str());
  }

  // 256 levels are read; one more is refused where it opens, and 10,000
  // (arrays or objects) are refused the same way, without exhausting the stack.
  void nestingDepth() {
    std::string error;
    const std::string ok = std::string(hs::kMaxJsonDepth, '[') + std::string(hs::kMaxJsonDepth, ']');
    QVERIFY2(hs::parseJson(ok, error), error.c_str());
    const std::string deeper = std::string(hs::kMaxJsonDepth + 1, '[') + std::string(hs::kMaxJsonDepth + 1, ']');
    QCOMPARE(refusal(deeper), "line 1, column 257: nested deeper than 256 levels");

    std::string arrays(10000, '[');
    arrays += std::string(10000, ']');
    QCOMPARE(refusal(arrays), "line 1, column 257: nested deeper than 256 levels");
    // {"k":{"k":...: each level is 5 characters, so level 257 opens at column 1281.
    std::string objects;
    for (int i = 0; i < 10000; ++i) objects += "{\"k\":";
    objects += "1" + std::string(10000, '}');
    QCOMPARE(refusal(objects), "line 1, column 1281: nested deeper than 256 levels");
    // Unclosed: still refused at the depth, not by running out of text first.
    QCOMPARE(refusal(std::string(10000, '[')), "line 1, column 257: nested deeper than 256 levels");
  }

  void largeStringsAreRead() {
    std::string big(1 << 20, 'x');
    for (size_t i = 0; i < big.size(); i += 997) big[i] = char('a' + i % 26);
    std::string error;
    const auto v = hs::parseJson("{\"s\": \"" + big + "\"}", error);
    QVERIFY2(v, error.c_str());
    QVERIFY(v->at("s").get<std::string>() == big);
  }

  // What a strict reader must still accept.
  void acceptsValidJson() {
    std::string error;
    const auto v = hs::parseJson("{\"a\": [1, -2.5e3, true, null, \"x\\\"\\u00e9\\ud83d\\ude00\"], \"b\": {},"
                                 " \"c\": 0.5E-2, \"d\": -0, \"e\": 1e308}\n",
                                 error);
    QVERIFY2(v, error.c_str());
    QCOMPARE(v->at("a")[1].get<double>(), -2500.0);
    QCOMPARE(v->at("a")[4].get<std::string>(), std::string("x\"\xc3\xa9\xf0\x9f\x98\x80"));
    QCOMPARE(v->at("c").get<double>(), 0.005);
    QCOMPARE(v->at("e").get<double>(), 1e308);
    const auto again = hs::parseJson(hs::writeJson(*v), error);
    QVERIFY2(again, error.c_str());
    QVERIFY(*again == *v);
    // Keys that repeat in different objects are not duplicates.
    QVERIFY2(hs::parseJson(R"({"x": {"a": 1}, "y": {"a": 2}, "z": [{"a": 3}, {"a": 4}]})", error), error.c_str());
    // Scalars at the top level are JSON too.
    QVERIFY2(hs::parseJson(" 3 ", error), error.c_str());
  }

  // Members stay in the order they were written, and text round-trips.
  void writerKeepsOrderAndRoundTrips() {
    Json o = Json::object();
    o["zebra"] = 1;
    o["apple"] = 2;
    o["mango"] = Json::array({3, "x"});
    QCOMPARE(hs::writeJson(o, -1), std::string(R"({"zebra":1,"apple":2,"mango":[3,"x"]})"));
    QCOMPARE(hs::writeJson(o, 2), std::string("{\n  \"zebra\": 1,\n  \"apple\": 2,\n  \"mango\": [\n    3,\n    \"x\"\n  ]\n}"));
    std::string error;
    const auto back = hs::parseJson(hs::writeJson(o), error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(hs::writeJson(*back), hs::writeJson(o));
  }

  // Doubles are written in a form that reads back to the same bits (the
  // shortest digits, not %.9g); JSON has no NaN, so non-finite is null.
  void numbersRoundTripExactly() {
    const double values[] = {0.1,
                             1.0 / 3.0,
                             2.0 / 3.0,
                             1e-300,
                             4.9406564584124654e-324,  // smallest subnormal
                             std::numeric_limits<double>::max(),
                             4412345.987654321,
                             512345.123456789,
                             -0.0,
                             0.000851788123456789,
                             123456789.123456789};
    for (double d : values) {
      std::string error;
      const auto r = hs::parseJson(hs::writeJson(Json(d)), error);
      QVERIFY2(r, error.c_str());
      QCOMPARE(bits(r->get<double>()), bits(d));
    }
    QCOMPARE(hs::writeJson(Json(0.1)), std::string("0.1"));
    QCOMPARE(hs::writeJson(Json(std::nan(""))), std::string("null"));
    QCOMPARE(hs::writeJson(Json(-std::numeric_limits<double>::infinity())), std::string("null"));
    // Whole numbers written as integers stay exact past 2^53.
    std::string error;
    const auto big = hs::parseJson("18446744073709551615", error);
    QVERIFY(big && big->get<uint64_t>() == std::numeric_limits<uint64_t>::max());
  }

  void writerReplacesInvalidUtf8() {
    const std::string text = hs::writeJson(Json(std::string("a\xff" "b")));
    QCOMPARE(text, std::string("\"a\xef\xbf\xbd" "b\""));
  }

  void locationOfAPath() {
    const std::string text =
        "{\n"
        "  \"name\": \"x\",\n"
        "  \"bindings\": [\n"
        "    {\"entity\": 3, \"tracks\": [{\"keys\": [1, 2]}, {\"keys\": [\n"
        "      {\"t\": 0}, {\"t\": \"late\"}]}]},\n"
        "    {\"a\\u0062\": [[], {\"\\\"q\": true}]}\n"
        "  ]\n"
        "}\n";
    std::string error;
    QVERIFY2(hs::parseJson(text, error), error.c_str());
    QCOMPARE(hs::jsonLocation(text, ""), std::string("line 1, column 1"));
    QCOMPARE(hs::jsonLocation(text, "name"), std::string("line 2, column 11"));
    QCOMPARE(hs::jsonLocation(text, "bindings"), std::string("line 3, column 15"));
    QCOMPARE(hs::jsonLocation(text, "bindings[0]"), std::string("line 4, column 5"));
    QCOMPARE(hs::jsonLocation(text, "bindings[0].entity"), std::string("line 4, column 16"));
    QCOMPARE(hs::jsonLocation(text, "bindings[0].tracks[0].keys[1]"), std::string("line 4, column 43"));
    QCOMPARE(hs::jsonLocation(text, "bindings[0].tracks[1].keys[1].t"), std::string("line 5, column 23"));
    // Keys are compared decoded ("a\u0062" is "ab").
    QCOMPARE(hs::jsonLocation(text, "bindings[1].ab[1].\"q"), std::string("line 6, column 30"));
    QCOMPARE(hs::jsonLocation(text, "bindings[1].ab[0]"), std::string("line 6, column 18"));
    // No such value.
    QCOMPARE(hs::jsonLocation(text, "bindings[2]"), std::string());
    QCOMPARE(hs::jsonLocation(text, "nothing"), std::string());
    // Columns count characters, not bytes.
    QCOMPARE(hs::jsonLocation("{\"é\": [\"ü\", 5]}", "é[1]"), std::string("line 1, column 13"));
  }

  // A document of the wrong shape gets a reader-level message naming what
  // it found, never a parser's "no error occurred".
  void readerNamesWhatItFound() {
    std::string error;
    const auto doc = hs::parseJson("[]", error);
    QVERIFY2(doc, error.c_str());
    hs::JsonReader r(error);
    QVERIFY(!r.object(*doc, ""));
    QCOMPARE(error, std::string("expected an object, not an array"));
    QCOMPARE(r.errorPath(), std::string());
  }

  void readerNamesThePathOfTheFirstBadValue() {
    std::string error;
    const auto doc = hs::parseJson(R"({"a": {"b": [1, "two", 3]}, "n": 1.5, "i": 7, "big": 1e20, "flag": 1,
                                     "v": [1, 2], "s": null})",
                                   error);
    QVERIFY2(doc, error.c_str());
    hs::JsonReader r(error);
    double d = 0;
    QVERIFY(r.number(doc->at("a")["b"][0], "a.b[0]", d));
    QCOMPARE(d, 1.0);
    QVERIFY(!r.number(doc->at("a")["b"][1], hs::jsonIndex(hs::jsonPath("a", "b"), 1), d));
    QCOMPARE(error, std::string("a.b[1]: expected a number, not a string"));
    QCOMPARE(r.errorPath(), std::string("a.b[1]"));
    // Later failures do not replace the first.
    bool flag = false;
    QVERIFY(!r.boolean(doc->at("flag"), "flag", flag));
    QCOMPARE(r.errorPath(), std::string("a.b[1]"));
    QVERIFY(r.failed());

    auto message = [&](auto read) {
      std::string e;
      hs::JsonReader fresh(e);
      read(fresh);
      return e;
    };
    int i = 0;
    int64_t i64 = 0;
    bool b = false;
    std::string s;
    double v3[3];
    QCOMPARE(message([&](hs::JsonReader& x) { x.integer(doc->at("n"), "n", i, 0, 10); }),
             std::string("n: expected a whole number from 0 to 10, not 1.5"));
    QCOMPARE(message([&](hs::JsonReader& x) { x.integer(doc->at("i"), "i", i, 0, 5); }),
             std::string("i: expected a whole number from 0 to 5, not 7"));
    QCOMPARE(message([&](hs::JsonReader& x) { x.integer(doc->at("big"), "big", i64, 0, 1000); }),
             std::string("big: expected a whole number from 0 to 1000, not 1e+20"));
    QCOMPARE(message([&](hs::JsonReader& x) { x.boolean(doc->at("flag"), "flag", b); }),
             std::string("flag: expected true or false, not a number"));
    QCOMPARE(message([&](hs::JsonReader& x) { x.numbers(doc->at("v"), "v", v3, 3, "[x, y, z]"); }),
             std::string("v: expected [x, y, z], not 2 values"));
    QCOMPARE(message([&](hs::JsonReader& x) { x.numbers(doc->at("n"), "n", v3, 3); }),
             std::string("n: expected 3 numbers, not a number"));
    QCOMPARE(message([&](hs::JsonReader& x) { x.string(doc->at("i"), "i", s); }),
             std::string("i: expected a string, not a number"));
    QCOMPARE(message([&](hs::JsonReader& x) { x.number(doc->at("n"), "n", d, 2.0, 3.0); }),
             std::string("n: expected a number from 2.0 to 3.0, not 1.5"));
    QCOMPARE(message([&](hs::JsonReader& x) { x.required(*doc, "", "missing"); }), std::string("missing: missing"));
    QCOMPARE(message([&](hs::JsonReader& x) { x.required(doc->at("a"), "a", "c"); }), std::string("a.c: missing"));

    // Whole numbers written as floats are whole numbers; optional members
    // that are absent or null leave the value alone.
    std::string e;
    hs::JsonReader ok(e);
    QVERIFY(ok.integer(Json(4.0), "x", i, 0, 10));
    QCOMPARE(i, 4);
    i = 9;
    QVERIFY(ok.optInteger(*doc, "", "absent", i, 0, 10));
    QVERIFY(ok.optInteger(*doc, "", "s", i, 0, 10));
    QCOMPARE(i, 9);
    QVERIFY(ok.optInteger(*doc, "", "i", i, 0, 10));
    QCOMPARE(i, 7);
    QVERIFY2(!ok.failed(), e.c_str());

    // A string that held an earlier message starts empty, so a new failure
    // is recorded and not mistaken for an old one.
    std::string stale = "an earlier message";
    hs::JsonReader again(stale);
    QVERIFY(!again.failed());
    QVERIFY(!again.boolean(doc->at("i"), "i", flag));
    QCOMPARE(stale, std::string("i: expected true or false, not a number"));
  }
};

QTEST_GUILESS_MAIN(TestCoreJson)
#include "test_core_json.moc"
