// The validation report (validate Report): its HTML page and case lines say what failed, with
// the page's text escaped.
#include <string>

#include <gtest/gtest.h>

#include "mvw/validate/Report.h"
#include "mvw/validate/Suite.h"

// GCC 12 at -O3 warns falsely (-Wrestrict, GCC bug 105651) on the test's std::string assignments
// once this small file inlines them; the test stays as written.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace mvw::validate {
namespace {

TEST(Report, HtmlAndCaseLinesSayWhatFailed) {
  Suite s;
  s.file = "suite.json";
  s.name = "golden <suite>";
  CaseSpec a, b;
  a.name = "a";
  b.name = "b";
  a.reference = "a.png";
  s.cases = {a, b};
  CaseResult ok, bad;
  bad.pass = false;
  bad.problems = {"mean delta 3.000 > 0.500"};
  const std::string page = reportHtml(s, {ok, bad}, {{"mvw_version", "9.9"}}, false);
  EXPECT_NE(page.find("<title>mvw validate: golden &lt;suite&gt;</title>"), std::string::npos);
  EXPECT_NE(page.find("1 of 2 cases pass"), std::string::npos);
  EXPECT_NE(page.find("mean delta 3.000 &gt; 0.500"), std::string::npos);
  EXPECT_NE(page.find("<td>9.9</td>"), std::string::npos);
  EXPECT_EQ(page.find("@BODY@"), std::string::npos);
  EXPECT_EQ(caseLine(b, bad).rfind("FAIL    b", 0), 0u);
  EXPECT_NE(caseLine(b, bad).find("mean delta 3.000"), std::string::npos);
}

}  // namespace
}  // namespace mvw::validate
