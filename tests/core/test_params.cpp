// core/params: parsing typed values against their declaration (numbers,
// whole numbers, tuples, choices, flags), the messages that name the option,
// the text and the range, clamping with warnings, and the report object.
#include <QtTest>

#include <cmath>
#include <limits>

#include "core/params.h"

using namespace hs;

namespace {

ParamDecl talus() {
  return {.key = "talus_deg", .option = "talus", .label = "Talus angle", .type = ParamType::Number, .unit = Unit::Degrees,
          .min = 0.0, .max = 90.0, .defaultValue = 35.0, .help = "angle of repose"};
}

ParamDecl iterations() {
  return {.key = "iterations", .option = "iterations", .label = "Iterations", .min = 1, .max = 1000000,
          .integer = true, .defaultValue = 50};
}

ParamDecl size() {
  return {.key = "size_px", .option = "size", .label = "Size", .unit = Unit::Pixels, .min = 1, .max = 16384,
          .integer = true, .valueName = "WxH", .count = 2, .separator = 'x'};
}

ParamDecl layout() {
  return {.key = "layout", .option = "layout", .label = "Layout", .type = ParamType::Choice, .defaultValue = "sbs",
          .choices = {"sbs", "tb", "h265|hevc"}};
}

std::string refused(const ParamDecl& p, const std::string& text) {
  std::string error;
  const auto v = parseParam(p, text, error);
  if (v) return "accepted: " + v->dump();
  return error;
}

}  // namespace

class TestParams : public QObject {
  Q_OBJECT

 private slots:
  void numbersInRangeAreAccepted() {
    std::string error;
    QCOMPARE(parseParam(talus(), "0", error)->get<double>(), 0.0);
    QCOMPARE(parseParam(talus(), "90", error)->get<double>(), 90.0);
    QCOMPARE(parseParam(talus(), "+12.5", error)->get<double>(), 12.5);
    QCOMPARE(parseParam(talus(), " 7 ", error)->get<double>(), 7.0);
    QVERIFY(error.empty());
  }

  void outOfRangeNamesOptionValueAndRange() {
    QCOMPARE(refused(talus(), "95"), std::string("--talus: 95 is out of range (0 to 90 degrees)"));
    QCOMPARE(refused(talus(), "-0.5"), std::string("--talus: -0.5 is out of range (0 to 90 degrees)"));
    // Just beyond the bound: the next double after 90.
    char beyond[64];
    std::snprintf(beyond, sizeof beyond, "%.17g", std::nextafter(90.0, 1000.0));
    QVERIFY(refused(talus(), beyond).find("out of range") != std::string::npos);
    // Too large for a double at all.
    QVERIFY(refused(talus(), "1e400").find("out of range") != std::string::npos);
  }

  void notANumberIsRefused() {
    QCOMPARE(refused(talus(), "steep"), std::string("--talus takes a number (0 to 90 degrees), not 'steep'"));
    for (const char* bad : {"", "nan", "inf", "-inf", "1,5", "12deg", "0x10", "++1"})
      QVERIFY2(refused(talus(), bad).rfind("--talus takes a number", 0) == 0, bad);
  }

  void wholeNumbers() {
    std::string error;
    const auto v = parseParam(iterations(), "1000000", error);
    QVERIFY(v && v->is_number_integer());
    QCOMPARE(v->get<long long>(), 1000000LL);
    QCOMPARE(refused(iterations(), "2.5"), std::string("--iterations takes a whole number (1 to 1000000), not '2.5'"));
    QCOMPARE(refused(iterations(), "1e3"), std::string("--iterations takes a whole number (1 to 1000000), not '1e3'"));
    QCOMPARE(refused(iterations(), "0"), std::string("--iterations: 0 is out of range (1 to 1000000)"));
    QCOMPARE(refused(iterations(), "1000001"), std::string("--iterations: 1000001 is out of range (1 to 1000000)"));
    // Beyond 64 bits: out of range, not wrapped round.
    QCOMPARE(refused(iterations(), "99999999999999999999"),
             std::string("--iterations: 99999999999999999999 is out of range (1 to 1000000)"));
  }

  void tuples() {
    std::string error;
    const auto v = parseParam(size(), "1920x1080", error);
    QVERIFY(v && v->is_array() && v->size() == 2);
    QCOMPARE((*v)[0].get<int>(), 1920);
    QCOMPARE((*v)[1].get<int>(), 1080);
    QCOMPARE(refused(size(), "10y"), std::string("--size takes WxH (1 to 16384 pixels each), not '10y'"));
    QCOMPARE(refused(size(), "12x"), std::string("--size takes WxH (1 to 16384 pixels each), not '12x'"));
    QCOMPARE(refused(size(), "1x2x3"), std::string("--size takes WxH (1 to 16384 pixels each), not '1x2x3'"));
    QCOMPARE(refused(size(), "99999x10"), std::string("--size: 99999 in '99999x10' is out of range (1 to 16384 pixels each)"));
    QCOMPARE(refused(size(), "0x10"), std::string("--size: 0 in '0x10' is out of range (1 to 16384 pixels each)"));
    // One number for all only where declared so.
    QVERIFY(!parseParam(size(), "100", error));
    ParamDecl square = size();
    square.oneForAll = true;
    const auto sq = parseParam(square, "100", error);
    QVERIFY(sq && (*sq)[0] == 100 && (*sq)[1] == 100);
    QCOMPARE(formatParamValue(square, *sq), std::string("100x100"));
  }

  void orderedTuplesAndRangesOfTheirOwn() {
    ParamDecl height{.key = "height_m", .option = "height", .label = "Height range", .unit = Unit::Metres,
                     .min = -100.0, .max = 100.0, .valueName = "MIN,MAX", .count = 2};
    height.ordered = true;
    std::string error;
    QVERIFY(parseParam(height, "-100,100", error));
    QVERIFY(parseParam(height, "5,5", error));
    QCOMPARE(refused(height, "9,1"), std::string("--height: '9,1' is not in order (MIN <= MAX)"));
    QVERIFY(!checkParam(height, Json::array({9, 1}), error));
    QCOMPARE(rangeText(height), std::string("-100 to 100 metres each, MIN <= MAX"));

    ParamDecl budget{.key = "budget_pct", .option = "budget", .label = "Budget", .unit = Unit::Percent,
                     .min = -100.0, .max = 100.0, .valueName = "N,F", .count = 2};
    budget.componentRanges = {{-100.0, 0.0}, {0.0, 100.0}};
    QVERIFY(parseParam(budget, "-100,100", error));
    QVERIFY(parseParam(budget, "0,0", error));
    QCOMPARE(refused(budget, "2,-1"), std::string("--budget: 2 in '2,-1' is out of range (-100 to 0, 0 to 100 percent)"));
    QVERIFY(!parseParam(budget, "-1,-0.5", error));
    QVERIFY(!checkParam(budget, Json::array({1, 2}), error));
    QCOMPARE(componentMin(budget, 1), 0.0);
    QCOMPARE(componentMax(budget, 0), 0.0);
  }

  void choicesAndAliases() {
    std::string error;
    QCOMPARE(parseParam(layout(), "tb", error)->get<std::string>(), std::string("tb"));
    QCOMPARE(parseParam(layout(), "hevc", error)->get<std::string>(), std::string("h265"));
    QCOMPARE(refused(layout(), "diagonal"), std::string("--layout: 'diagonal' is not one of sbs, tb, h265"));
    QVERIFY(checkParam(layout(), Json("sbs"), error));
    QVERIFY(!checkParam(layout(), Json("x"), error));
    QVERIFY(!checkParam(layout(), Json(3), error));
  }

  void flags() {
    const ParamDecl f{.key = "hills", .option = "hills", .label = "Hills", .type = ParamType::Flag};
    std::string error;
    QCOMPARE(parseParam(f, "true", error)->get<bool>(), true);
    QCOMPARE(parseParam(f, "0", error)->get<bool>(), false);
    QVERIFY(!parseParam(f, "maybe", error));
    QVERIFY(error.find("--hills") != std::string::npos);
  }

  void checkValuesThatDidNotComeAsText() {
    std::string error;
    QVERIFY(checkParam(talus(), Json(45.0), error));
    QVERIFY(!checkParam(talus(), Json(95.0), error));
    QCOMPARE(error, std::string("--talus: 95 is out of range (0 to 90 degrees)"));
    QVERIFY(!checkParam(talus(), Json(std::numeric_limits<double>::quiet_NaN()), error));
    QVERIFY(!checkParam(talus(), Json("35"), error));
    QVERIFY(!checkParam(iterations(), Json(2.5), error));
    QVERIFY(checkParam(size(), Json::array({1, 16384}), error));
    QVERIFY(!checkParam(size(), Json::array({1, 16385}), error));
    QVERIFY(!checkParam(size(), Json::array({1}), error));
  }

  void clampingWarnsAndRepairs() {
    std::vector<std::string> w;
    QCOMPARE(clampParam(talus(), 45.0, w), 45.0);
    QVERIFY(w.empty());
    QCOMPARE(clampParam(talus(), 95.0, w, "thermal erosion"), 90.0);
    QCOMPARE(w.size(), size_t(1));
    QCOMPARE(w[0], std::string("thermal erosion: Talus angle 95 is out of range (0 to 90 degrees); using 90"));
    QCOMPARE(clampParam(talus(), -1e300, w), 0.0);
    QCOMPARE(clampParam(talus(), std::numeric_limits<double>::quiet_NaN(), w), 35.0);
    QVERIFY(w.back().find("not a number; using 35") != std::string::npos);
    QCOMPARE(w.size(), size_t(3));
    // Whole numbers are rounded into range.
    QCOMPARE(clampParam(iterations(), 0.0, w), 1.0);
    QCOMPARE(clampParam(iterations(), 2.4, w), 2.0);
    QCOMPARE(clampParam(iterations(), 1e12, w), 1e6);
  }

  void helpAndNames() {
    QCOMPARE(paramHelp(talus()), std::string("angle of repose (0 to 90 degrees; default 35)"));
    QCOMPARE(paramHelp(layout()), std::string("sbs, tb, h265; default sbs"));
    ParamDecl noOption = talus();
    noOption.option.clear();
    QCOMPARE(paramName(noOption), std::string("Talus angle"));
    QCOMPARE(rangeText(size()), std::string("1 to 16384 pixels each"));
  }

  void numbersFormatShortestExact() {
    QCOMPARE(formatNumber(1e6), std::string("1000000"));
    QCOMPARE(formatNumber(0.1), std::string("0.1"));
    QCOMPARE(formatNumber(-11000), std::string("-11000"));
    QCOMPARE(formatNumber(1e-4), std::string("0.0001"));
    QCOMPARE(formatNumber(1e-6), std::string("1e-06"));
    QCOMPARE(formatNumber(3.4028234663852886e38), std::string("3.4028234663852886e+38"));
    for (double v : {0.1, 1.0 / 3.0, 1e-6, 2.5e-300, 6.02214076e23})
      QCOMPARE(std::stod(formatNumber(v)), v);
  }

  void operationsAndReports() {
    OperationDecl op{.name = "terrain erode", .summary = "erosion"};
    op.params = {talus(), iterations(), size()};
    QCOMPARE(&op.param("iterations"), &op.params[1]);
    QVERIFY(!op.find("rain"));
    QVERIFY_THROWS_EXCEPTION(std::logic_error, op.param("rain"));
    // Declared keys in declaration order; given values win over defaults;
    // keys without a value or default are left out, undeclared keys too.
    const Json values = {{"iterations", 7}, {"talus_deg", 20.0}, {"colour", "red"}};
    const Json report = paramsJson(op, values);
    QCOMPARE(report.dump(), std::string(R"({"talus_deg":20.0,"iterations":7})"));
    QCOMPARE(paramsJson(op, Json::object()).dump(), std::string(R"({"talus_deg":35.0,"iterations":50})"));
  }
};

QTEST_GUILESS_MAIN(TestParams)
#include "test_params.moc"
