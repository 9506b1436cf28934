// Hostile input to the scene-file and --set parsers (tag [core]): nesting deep enough to
// overflow a recursion, text that toml++ 3.3.0 mishandles, and the messages a student gets.
#include "lab_testing.hpp"
#include "springlab/errors.hpp"
#include "springlab/parameters.hpp"
#include "springlab/real_text.hpp"
#include "springlab/scene_file.hpp"
#include "springlab/scene_text.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

using namespace springlab;
using namespace springlab::testing;
using lab_catch::Contains;

namespace {

std::string scene_rejection(const std::string& text) {
  return rejection([&] { parse_scene(text, "s.toml"); });
}

std::string repeated(const std::string& piece, int times, const std::string& separator) {
  std::string text;
  for (int i = 0; i < times; ++i)
    text += (i ? separator : "") + piece;
  return text;
}

}  // namespace

TEST_CASE("Scene files: deep nesting is refused before parsing, with the line and the depth",
          "[core][scene-input]") {
  INFO("20,000 levels overflowed the stack of the recursion over the tables (SIGSEGV)");
  const std::string header = "rows = 2\n[" + repeated("t", 20000, ".") + "]\nx = 1\n";
  CHECK_THAT(scene_rejection(header),
             Contains("s.toml:2") && Contains("nested 20000 levels") && Contains("at most 8"));
  const std::string dotted = "\n\n" + repeated("t", 20000, ".") + " = 1\n";
  CHECK_THAT(scene_rejection(dotted),
             Contains("s.toml:3") && Contains("nested 20000 levels") && Contains("at most 8"));
  const std::string inline_tables =
      "a = " + repeated("{b = ", 5000, "") + "1" + repeated("}", 5000, "") + "\n";
  CHECK_THAT(scene_rejection(inline_tables), Contains("s.toml:1") && Contains("nested 5001"));
  const std::string arrays = "a = " + repeated("[", 5000, "") + repeated("]", 5000, "") + "\n";
  CHECK_THAT(scene_rejection(arrays), Contains("s.toml:1") && Contains("nested 5001"));
  // The kit's deepest keys, three levels, in every form TOML allows.
  CHECK_NOTHROW(parse_scene("wind.direction.x = 0.5\n[gravity]\ny = -1\n", "s.toml"));
  CHECK_NOTHROW(parse_scene("wind = {direction = {x = 1, y = 0.5}}\n", "s.toml"));
  // Eight levels are allowed (then refused as unknown keys), nine are not.
  CHECK_THAT(scene_rejection("a.b.c.d.e.f.g.h = 1\n"), Contains("no parameter"));
  CHECK_THAT(scene_rejection("[a.b.c.d]\ne.f.g = {h = [1]}\n"), Contains("nested 9 levels"));
  // Dots inside quoted keys, strings and comments are no nesting.
  CHECK_THAT(scene_rejection("\"a.b.c.d.e.f.g.h.i\" = 1 # .........\n"), Contains("no parameter"));
  CHECK_NOTHROW(parse_scene("name = \"a.b.c.d.e.f.g.h.i.j\" # k.l.m.n.o.p.q.r.s\n", "s.toml"));
}

TEST_CASE("Scene files: text that toml++ 3.3.0 mishandles is refused before it reaches it",
          "[core][scene-input]") {
  INFO("non-ASCII outside strings reaches an unreachable point, '[#' a false assumption");
  CHECK_THAT(scene_rejection("rows = 2\n\xC3\xA2\n"),
             Contains("s.toml:2") && Contains("U+00E2") && Contains("inside \"strings\""));
  CHECK_THAT(scene_rejection("a = [\xC3\xA2]\n"), Contains("s.toml:1") && Contains("U+00E2"));
  CHECK_THAT(scene_rejection("\n[# #\n"), Contains("s.toml:2") && Contains("table header"));
  CHECK_THAT(scene_rejection("[[ =\n"), Contains("s.toml:1") && Contains("table header"));
  CHECK_THAT(scene_rejection("name = \"a\xFF\"\n"), Contains("s.toml:1") && Contains("UTF-8"));
  CHECK_THAT(scene_rejection("# \xC3\n"), Contains("UTF-8"));
  CHECK_THAT(scene_rejection("rows = 2\x1B\n"), Contains("s.toml:1") && Contains("U+001B"));
  // Found by fuzzing check_scene_text in front of a sanitized header-only toml++ 3.3.0: a '}'
  // as an array element, a quote inside a bare value, a backslash before non-ASCII text (also
  // after a line-ending backslash), a lone carriage return.
  CHECK_THAT(scene_rejection("a = [1, }\n"), Contains("s.toml:1") && Contains("inside an array"));
  CHECK_THAT(scene_rejection("a = [1, #\n 2'\xC3\xA2'\n]\n"),
             Contains("s.toml:2") && Contains("U+00E2"));
  CHECK_THAT(scene_rejection("a=-x=[\"\xC3\xA2\"]\n"), Contains("U+00E2"));
  CHECK_THAT(scene_rejection("name = \"\"\"a\\\xC3\xA2\"\"\"\n"), Contains("backslash"));
  CHECK_THAT(scene_rejection("name = \"\"\"a\\ \n\t\xC3\xA2\"\"\"\n"), Contains("backslash"));
  CHECK_THAT(scene_rejection("a = 3-\r\r\n"), Contains("U+000D"));
  CHECK_NOTHROW(parse_scene("name = \"\"\"a\\\r\n  b\"\"\"\r\nrows = 2\r\n", "s.toml"));
  // Arrays of NaN and infinities: the error is said without toml++'s printer, whose layout
  // code converts log10(NaN) to an integer.
  CHECK_THAT(scene_rejection("a=[nan]\n"), Contains("s.toml:1: a = [nan] (an array)"));
  CHECK_THAT(scene_rejection("mass=[-inf, nan]\n"),
             Contains("s.toml:1: mass = [-inf, nan] (an array): expected a number"));
  CHECK_THAT(scene_rejection("mass = nan\n"), Contains("mass = nan kg: allowed 1e-06 <= mass"));
  // A byte-order mark (Notepad writes one) starts the file; elsewhere it is a character outside
  // quotes.
  CHECK(parse_scene("\xEF\xBB\xBFrows = 3\r\n", "s.toml").rows == 3);
  CHECK_THAT(scene_rejection("rows = 3\n\xEF\xBB\xBF"), Contains("U+FEFF"));
  // Non-ASCII text stays allowed where TOML allows it: in strings and comments.
  CHECK(parse_scene("name = \"Tr\xC3\xA4gheit\" # \xC3\xA2\n", "s.toml").name == "Tr\xC3\xA4gheit");
}

TEST_CASE("Scene files: a number TOML cannot hold says what the key allows",
          "[core][scene-input]") {
  // toml++'s own words name the syntax only; the kit adds the parameter's range.
  CHECK_THAT(
      scene_rejection("mass = 1e999\n"),
      Contains("s.toml:1") && Contains("1e999") && Contains("; allowed 1e-06 <= mass <= 1e+09 kg"));
  CHECK_THAT(scene_rejection("cols = 2\n  rows =99999999999999999999999\n"),
             Contains("s.toml:2") && Contains("; allowed 1 <= rows <= 1e+05 (a whole number)"));
  CHECK_THAT(scene_rejection("title = 1e999\n"), !Contains("allowed"));  // no such parameter
  CHECK_THAT(scene_rejection("rows = 2\nrows = 3\n"),  // a duplicate: no range to give
             Contains("s.toml:2") && !Contains("allowed"));
}

TEST_CASE("Scene files: values are quoted as the file writes them", "[core][scene-input]") {
  CHECK_THAT(scene_rejection("mas = 0.20000000000000001\n"),
             Contains("s.toml:1: mas = 0.20000000000000001 (a number)"));
  CHECK_THAT(scene_rejection("rows = 9223372036854775807\n"),
             Contains("s.toml:1: rows = 9223372036854775807: allowed 1 <= rows"));
  CHECK_THAT(scene_rejection("mass = 1_000e9\n"), Contains("mass = 1_000e9 kg: allowed"));
  CHECK_THAT(scene_rejection("rows = \"3\"\n"), Contains("rows = \"3\" (a string): expected"));
  CHECK_THAT(scene_rejection("rows = 0x7FFFFFFF\n"), Contains("rows = 0x7FFFFFFF: allowed"));
}

TEST_CASE("Scene files: unknown keys and empty unknown tables are refused with a useful hint",
          "[core][scene-input]") {
  CHECK_THAT(scene_rejection("rows = 3\n[foo]\n"),
             Contains("s.toml:2: foo = {} (an empty table)") && Contains("there is no parameter"));
  CHECK_THAT(scene_rejection("foo = {}\n"), Contains("there is no parameter \"foo\""));
  CHECK_NOTHROW(parse_scene("[structural]\n[wind.direction]\n", "s.toml"));
  const std::string far = scene_rejection("foo.bar = 1\n");
  CHECK_THAT(far, !Contains("did you mean") && Contains("--help"));
  CHECK_THAT(scene_rejection("mas = 1\n"), Contains("did you mean \"mass\""));
  CHECK_THAT(scene_rejection("shear.stiffness = 1\n"),
             Contains("shear.enabled, shear.k, shear.b, shear.rest_length"));
}

TEST_CASE("Scene files: control characters in strings are refused, not printed",
          "[core][scene-input]") {
  const std::string escape = scene_rejection("name = \"a\\u001b[31mred\"\n");
  CHECK_THAT(escape, Contains("s.toml:1: name = \"a\\u001b[31mred\"") && Contains("control"));
  CHECK(escape.find('\x1B') == std::string::npos);
  CHECK_THAT(scene_rejection("pinned = \"\\u009b1\"\n"), Contains("control"));
  CHECK_THAT(scene_rejection("name = \"\"\n"), Contains("name = \"\"") && Contains("empty"));
}

TEST_CASE("Option --set: every bad value is named with the key, the text as written and the range",
          "[core][scene-input]") {
  SceneParameters p;
  const auto set = [&](const char* assignment) {
    return rejection([&] { set_assignment(p, assignment); });
  };
  for (const char* bad : {"mass=", "mass=+1", "mass=1kg", "mass= 1", "mass=1 "}) {
    CAPTURE(bad);
    const std::string written = std::string(bad).substr(5);
    CHECK_THAT(set(bad), Contains("mass = \"" + written +
                                  "\": not a number; allowed 1e-06 <= mass <= 1e+09 kg"));
  }
  for (const char* bad : {"mass=1e999", "mass=1e-999"}) {
    CAPTURE(bad);
    CHECK_THAT(set(bad),
               Contains("\": beyond the range of a double; allowed 1e-06 <= mass <= 1e+09"));
  }
  for (const char* bad : {"mass=nan", "mass=-nan", "mass=inf", "mass=infinity", "mass=-INF"}) {
    CAPTURE(bad);
    const std::string written = std::string(bad).substr(5);
    CHECK_THAT(set(bad), Contains("mass = " + written + " kg: allowed 1e-06 <= mass <= 1e+09 kg"));
  }
  CHECK_THAT(set("rows=9223372036854775807"),
             Contains("rows = 9223372036854775807: allowed 1 <= rows <= 1e+05"));
  CHECK_THAT(set("rows=2.5"), Contains("rows = 2.5: allowed") && Contains("a whole number"));
  CHECK_THAT(set("shear.enabled="), Contains("shear.enabled = \"\": true or false"));
  CHECK_THAT(set("integrator="), Contains("integrator = \"\"") && Contains("empty"));
  CHECK_THAT(set("name=a\x1B[2Jb"), Contains("name = \"a\\x1B[2Jb\"") && Contains("control"));
  const std::string key = set("\x1B[2J=1");
  CHECK_THAT(key, Contains("\\x1B[2J") && Contains("there is no parameter"));
  CHECK(key.find('\x1B') == std::string::npos);
  CHECK_THAT(set("foo.bar=1"), !Contains("did you mean") && Contains("--help"));
  CHECK_THAT(set("strcutural.k=1"), Contains("did you mean \"structural.k\""));
  CHECK(p.mass == SceneParameters{}.mass);  // nothing was set on the way
}

TEST_CASE("Messages show what could act on a terminal, escaped", "[core][scene-input]") {
  // A tester's find: bytes that are not UTF-8 (0x9B is the 8-bit CSI of some terminals) and
  // Unicode's bidirectional controls (U+202E turns the text after it around) reached the
  // terminal raw.
  CHECK(printable("a\x9B[2Jb") == "a\\x9B[2Jb");
  CHECK(printable("a\xE2\x80\xAE"
                  "b") == "a\\u202Eb");
  CHECK(printable("a\xD8\x9C"
                  "b") == "a\\u061Cb");  // the Arabic letter mark
  CHECK(printable("a\x1B[31mb\xC2\x9B") == "a\\x1B[31mb\\xC2\\x9B");
  CHECK(printable("Tr\xC3\xA4gheit \xE2\x82\xAC") == "Tr\xC3\xA4gheit \xE2\x82\xAC");  // kept
  CHECK(printable_lines("line 1\n\tline\x1B 2") == "line 1\n\tline\\x1B 2");
}

TEST_CASE("Messages quote a long text by its start and its length", "[core][scene-input]") {
  // A tester's find: --dt with 100,000 digits was echoed whole, a 200 KB message.
  const std::string digits(100000, '1');
  const std::string quoted = quoted_for_terminal(digits);
  CHECK(quoted == "\"" + digits.substr(0, 100) + "...\" (100000 bytes)");
  CHECK(quoted_for_terminal(std::string(120, 'a')) == "\"" + std::string(120, 'a') + "\"");
  // So are the values and keys of --set (a tester's third round).
  SceneParameters p;
  for (const std::string& assignment : {"structural.k=" + digits, digits + "=1"}) {
    std::string message;
    try {
      set_assignment(p, assignment);
    } catch (const InvalidParameter& error) {
      message = error.what();
    }
    CAPTURE(message.substr(0, 300));
    CHECK_THAT(message, Contains("...\" (100000 bytes)"));
    CHECK(message.size() < 1000);
  }
  // Cut between characters, never inside one (each "\xC3\xA4" is one).
  std::string umlauts;
  for (int i = 0; i < 100; ++i)
    umlauts += "\xC3\xA4";
  CHECK(quoted_for_terminal(umlauts) == "\"" + umlauts.substr(0, 100) + "...\" (200 bytes)");
}

TEST_CASE("Messages write numbers as std::to_chars does, also where the library has no to_chars",
          "[core][scene-input]") {
  INFO(
      "shortest_text_portable stands in for std::to_chars(double) where libc++ has none (the "
      "page in a browser, viewer/web/): its text must be to_chars's, or the page's messages "
      "would differ from the runner's");
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> values{0.0, -0.0, 0.01, 1e-6, 1e5, 123456.0, 1e21, 1e22, 5e-324, 9.81};
  for (const double x : {-2.5, 0.3, 0.1 + 0.2, 1e300, -inf, inf, 12345678901234567890.0})
    values.push_back(x);
  values.push_back(std::numeric_limits<double>::max());
  std::uint64_t bits = 0x9e3779b97f4a7c15;  // a fixed sequence of bit patterns (xorshift64)
  for (int i = 0; i < 20000; ++i) {
    bits ^= bits << 13;
    bits ^= bits >> 7;
    bits ^= bits << 17;
    double x;
    std::memcpy(&x, &bits, sizeof x);
    if (std::isfinite(x)) values.push_back(x);
    values.push_back(double(std::int64_t(bits % 2000001) - 1000000) / 1000.0);  // "-12.345"
  }
  int differing = 0;
  std::string first;
  for (const double x : values) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, x).ptr;
    const std::string expected(text, end), written = shortest_text_portable(x);
    if (written == expected) continue;
    if (differing++ == 0) first = "to_chars wrote " + expected + ", the portable text " + written;
  }
  CAPTURE(values.size(), first);
  CHECK(differing == 0);
}
