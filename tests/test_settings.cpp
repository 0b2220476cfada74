// Tests for the solver settings (core/config/settings.h) and their one typed reader
// (core/config/solver_settings.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/util/errors.h"
#include "search/screening.h"
#include "tests/test_support_messages.h"

namespace disco {
namespace {

const char* const kFile = "disco.yaml";

// Line numbers below refer to this text (1-based).
const char* const kText = R"(# solver settings
ipopt:
  sb: "yes"
  print_level: 0
  tol: 1.0e-9
elastic:
  zeta: 10.0
  polish: true
  formulation: lumped
  rounds: 7
  limit: .inf
  label: "7"
empty:
list: [1, 2]
)";

Settings make() { return Settings::parse(kText, kFile); }

// Runs `f`, which must throw InputError; returns the message.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("wrong exception type: ") + e.what();
  }
  return "no exception";
}

using test_support::expect_prefix;

using test_support::temp_path;

TEST(Settings, TypedValues) {
  const Settings s = make();
  EXPECT_EQ(s.source(), kFile);
  EXPECT_DOUBLE_EQ(s.number("elastic.zeta"), 10.0);
  EXPECT_DOUBLE_EQ(s.number("ipopt.tol"), 1e-9);
  EXPECT_DOUBLE_EQ(s.number("elastic.rounds"), 7.0);
  EXPECT_EQ(s.number("elastic.limit"), HUGE_VAL);
  EXPECT_EQ(s.integer("elastic.rounds"), 7);
  EXPECT_EQ(s.integer("list.1"), 2);
  EXPECT_TRUE(s.boolean("elastic.polish"));
  EXPECT_EQ(s.text("elastic.formulation"), "lumped");
  EXPECT_EQ(s.text("elastic.label"), "7");
  EXPECT_EQ(s.text("ipopt.sb"), "yes");
}

TEST(Settings, TypeErrors) {
  const Settings s = make();
  expect_prefix(error_of([&] { s.integer("elastic.zeta"); }),
                "disco.yaml:7: key 'elastic.zeta': ", "must be an integer (got '10.0')");
  expect_prefix(error_of([&] { s.number("elastic.formulation"); }),
                "disco.yaml:9: key 'elastic.formulation': ", "must be a number");
  expect_prefix(error_of([&] { s.number("elastic.label"); }),
                "disco.yaml:12: key 'elastic.label': ", "quoted string");
  expect_prefix(error_of([&] { s.boolean("elastic.formulation"); }),
                "disco.yaml:9: key 'elastic.formulation': ", "true or false");
  expect_prefix(error_of([&] { s.number("elastic"); }),
                "disco.yaml:7: key 'elastic': ", "got a mapping");
  expect_prefix(error_of([&] { s.text("list"); }), "disco.yaml:14: key 'list': ", "got a sequence");
  expect_prefix(error_of([&] { s.number("elastic.missing"); }),
                "disco.yaml:7: key 'elastic.missing': ", "missing");
  expect_prefix(error_of([&] { s.number("nothing.here"); }),
                "disco.yaml: key 'nothing.here': ", "missing");
}

TEST(Settings, Section) {
  const Settings s = make();
  const std::vector<Settings::Entry> e = s.section("ipopt");
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0].name, "sb");
  EXPECT_EQ(e[0].value, "yes");
  EXPECT_EQ(e[0].line, 3);
  EXPECT_EQ(e[1].name, "print_level");
  EXPECT_EQ(e[1].value, "0");
  EXPECT_EQ(e[2].name, "tol");
  EXPECT_EQ(e[2].value, "1.0e-9");
  EXPECT_EQ(e[2].line, 5);
  EXPECT_TRUE(s.section("empty").empty());
  expect_prefix(error_of([&] { s.section("list"); }),
                "disco.yaml:14: key 'list': ", "must be a section");
  expect_prefix(error_of([&] { s.section("solver"); }), "disco.yaml: key 'solver': ", "missing");
  const Settings nested = Settings::parse("ipopt:\n  a: 1\n  b: [1]\n", kFile);
  expect_prefix(error_of([&] { nested.section("ipopt"); }),
                "disco.yaml:3: key 'ipopt.b': ", "single value");
}

TEST(Settings, Where) {
  Settings s = make();
  EXPECT_EQ(s.where("elastic.zeta"), "disco.yaml:7");
  EXPECT_EQ(s.where("ipopt"), "disco.yaml:3");
  EXPECT_EQ(s.where("no.such"), "disco.yaml");
  s.apply_override("elastic.zeta=5");
  EXPECT_EQ(s.where("elastic.zeta"), "--set");
}

TEST(Settings, Overrides) {
  Settings s = make();
  s.apply_override("elastic.zeta=100");
  s.apply_override("elastic.polish=false");
  s.apply_override("elastic.formulation=per_pair");
  s.apply_override("ipopt.print_level=5");
  s.apply_override("ipopt.max_iter=50");
  s.apply_override("list.0=4");
  EXPECT_DOUBLE_EQ(s.number("elastic.zeta"), 100);
  EXPECT_FALSE(s.boolean("elastic.polish"));
  EXPECT_EQ(s.text("elastic.formulation"), "per_pair");
  EXPECT_EQ(s.integer("list.0"), 4);
  const std::vector<Settings::Entry> e = s.section("ipopt");
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[1].name, "print_level");
  EXPECT_EQ(e[1].value, "5");
  EXPECT_EQ(e[1].line, 0);
  EXPECT_EQ(e[2].line, 5);
  EXPECT_EQ(e[3].name, "max_iter");  // new options come last
  EXPECT_EQ(e[3].value, "50");
  EXPECT_EQ(e[3].line, 0);
  // An ipopt section is created when the file has none.
  Settings bare = Settings::parse("elastic:\n  zeta: 1\n", kFile);
  bare.apply_override("ipopt.tol=1e-6");
  ASSERT_EQ(bare.section("ipopt").size(), 1u);
  EXPECT_EQ(bare.section("ipopt")[0].value, "1e-6");
}

TEST(Settings, OverrideErrors) {
  Settings s = make();
  expect_prefix(error_of([&] { s.apply_override("elastic.zeta"); }),
                "--set: key 'elastic.zeta': ", "KEY=VALUE");
  expect_prefix(error_of([&] { s.apply_override("elastic.zetta=1"); }),
                "--set: key 'elastic.zetta': ", "no such setting");
  expect_prefix(error_of([&] { s.apply_override("solver.tol=1"); }),
                "--set: key 'solver.tol': ", "no such setting");
  expect_prefix(error_of([&] { s.apply_override("elastic=1"); }),
                "--set: key 'elastic': ", "is a section");
  expect_prefix(error_of([&] { s.apply_override("elastic..zeta=1"); }),
                "--set: key 'elastic..zeta': ", "malformed");
  expect_prefix(error_of([&] { s.apply_override("elastic.zeta=[1, 2]"); }),
                "--set: key 'elastic.zeta': ", "single scalar");
  expect_prefix(error_of([&] { s.apply_override("elastic.zeta="); }),
                "--set: key 'elastic.zeta': ", "needs a value");
  expect_prefix(error_of([&] { s.apply_override("elastic.zeta=[1"); }),
                "--set: key 'elastic.zeta': ", "cannot parse");
  // A wrong type given on the command line is reported as "--set" when used.
  s.apply_override("elastic.rounds=2.5");
  expect_prefix(error_of([&] { s.integer("elastic.rounds"); }),
                "--set: key 'elastic.rounds': ", "must be an integer (got '2.5')");
}

TEST(Settings, CopiesAreIndependent) {
  const Settings original = make();
  Settings copy = original;
  copy.apply_override("elastic.zeta=3");
  EXPECT_DOUBLE_EQ(copy.number("elastic.zeta"), 3);
  EXPECT_DOUBLE_EQ(original.number("elastic.zeta"), 10);
  EXPECT_EQ(original.where("elastic.zeta"), "disco.yaml:7");
  Settings assigned;
  assigned = original;
  assigned.apply_override("elastic.zeta=4");
  EXPECT_DOUBLE_EQ(original.number("elastic.zeta"), 10);
}

TEST(Settings, BadDocuments) {
  expect_prefix(error_of([] { Settings::parse("a: 1\nb: [1\n", kFile); }),
                "disco.yaml:", "YAML syntax error");
  expect_prefix(error_of([] { Settings::parse("a:\n  b: 1\n  b: 2\n", kFile); }),
                "disco.yaml:3: key 'a.b': ", "duplicate key");
  expect_prefix(error_of([] { Settings::parse("- 1\n", kFile); }),
                "disco.yaml:1: ", "must be a YAML mapping");
  const Settings empty = Settings::parse("", kFile);
  expect_prefix(error_of([&] { empty.number("a"); }), "disco.yaml: key 'a': ", "missing");
}

TEST(Settings, LoadFile) {
  const std::string path = temp_path("disco.yaml");
  {
    std::ofstream out(path);
    out << kText;
  }
  const Settings s = Settings::load(path);
  EXPECT_EQ(s.source(), path);
  EXPECT_EQ(s.where("elastic.zeta"), path + ":7");
  expect_prefix(error_of([&] { s.integer("elastic.zeta"); }),
                path + ":7: key 'elastic.zeta': ", "integer");
  std::filesystem::remove(path);
  const std::string msg = error_of([&] { Settings::load(path); });
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("cannot open"), std::string::npos) << msg;
}

TEST(Settings, SplitOverrides) {
  std::vector<std::string> scene, settings;
  split_overrides({"scene.steps=25", "elastic.zeta=1", "scene.robots.0.mass=2", "ipopt.tol=1"},
                  scene, settings);
  EXPECT_EQ(scene, (std::vector<std::string>{"steps=25", "robots.0.mass=2"}));
  EXPECT_EQ(settings, (std::vector<std::string>{"elastic.zeta=1", "ipopt.tol=1"}));
  expect_prefix(error_of([&] { split_overrides({"scene.steps"}, scene, settings); }),
                "--set: key 'scene.steps': ", "KEY=VALUE");
  expect_prefix(error_of([&] { split_overrides({"=3"}, scene, settings); }),
                "--set: key '=3': ", "empty key");
}

// The test binary (BUILD/tests) finds its default settings at BUILD/share/disco/configs/
// disco.yaml, which is the source's configs/disco.yaml (a link made when CMake configures).
TEST(Settings, TheDefaultFileIsFoundBesideTheExecutable) {
  const std::string path = default_settings_path();
  const std::string tail = "/share/disco/configs/disco.yaml";
  ASSERT_GT(path.size(), tail.size());
  EXPECT_EQ(path.substr(path.size() - tail.size()), tail) << path;
  EXPECT_TRUE(std::filesystem::equivalent(path, std::string(DISCO_SOURCE_DIR) + "/configs/disco.yaml"))
      << path;
  EXPECT_EQ(Settings::load(path).source(), path);
}

// Every range check of the section readers, each naming the key ("--set" when overridden).
TEST(Settings, TheSectionReadersRefuseValuesOutOfRange) {
  struct Case {
    const char* assignment;
    const char* key;
    const char* what;
    bool reduction;  // reduction_settings (else elastic_settings)
  };
  const Case cases[] = {
      {"elastic.zeta=0", "elastic.zeta", "must be positive", false},
      {"elastic.zeta_factor=1", "elastic.zeta_factor", "must exceed 1", false},
      {"elastic.sigma_factor=1", "elastic.sigma_factor", "must be below 1", false},
      {"elastic.violation_tolerance=-1e-6", "elastic.violation_tolerance", "must be positive", false},
      {"elastic.formulation=tight", "elastic.formulation", "must be 'lumped', 'per_pair', 'relaxed' or 'barrier', got 'tight'", false},
      {"elastic.barrier_sigma_factor=0", "elastic.barrier_sigma_factor", "must be positive", false},
      {"elastic.barrier_sigma_exponent=-1", "elastic.barrier_sigma_exponent", "must be positive", false},
      {"elastic.barrier_mu=fast", "elastic.barrier_mu", "must be 'monotone' or 'adaptive', got 'fast'", false},
      {"elastic.polish_fixed_above=-1e-8", "elastic.polish_fixed_above", "must be >= 0", false},
      {"elastic.stagnation.after=-1", "elastic.stagnation.after", "must be >= 0", false},
      {"elastic.stagnation.window=0", "elastic.stagnation.window", "must be >= 1", false},
      {"elastic.stagnation.level=0", "elastic.stagnation.level", "must be positive", false},
      {"elastic.stagnation.decrease=1", "elastic.stagnation.decrease", "must be below 1", false},
      {"elastic.stagnation.late.after=-1", "elastic.stagnation.late.after", "must be >= 0", false},
      {"elastic.stagnation.late.window=0", "elastic.stagnation.late.window", "must be >= 1", false},
      {"elastic.stagnation.late.level=-1", "elastic.stagnation.late.level", "must be positive", false},
      {"elastic.stagnation.late.decrease=2", "elastic.stagnation.late.decrease", "must be below 1", false},
      {"feasibility.horizon_min=0", "feasibility.horizon_min", "must be positive", true},
      {"reduction.rate=1", "reduction.rate", "must be below 1", true},
      {"reduction.shrink=1.5", "reduction.shrink", "must be below 1", true},
      {"reduction.max_solves=-1", "reduction.max_solves", "must be >= 0", true},
      {"reduction.step_iterations=0", "reduction.step_iterations", "must be >= 1", true},
      {"reduction.segment_iterations=0", "reduction.segment_iterations", "must be >= 1", true},
      {"reduction.flip_rounds=-2", "reduction.flip_rounds", "must be >= 0", true},
      {"reduction.time_limit=-1", "reduction.time_limit", "must be >= 0", true},
      {"reduction.minimize_weak=fast", "reduction.minimize_weak", "must be 'penalty' or 'homotopy', got 'fast'", true},
  };
  for (const Case& c : cases) {
    Settings s = Settings::load(default_settings_path());
    s.apply_override(c.assignment);
    const std::string msg = error_of([&] {
      if (c.reduction) {
        reduction_settings(s);
      } else {
        elastic_settings(s);
      }
    });
    EXPECT_EQ(msg, std::string("--set: key '") + c.key + "': " + c.what) << c.assignment;
  }
  // In the file, the message names its line.
  const std::string file = temp_path("range.yaml");
  {
    std::ofstream out(file);
    out << "feasibility:\n  horizon_factor: 1.5\n  horizon_min: -1\n";
  }
  expect_prefix(error_of([&] { reduction_settings(Settings::load(file)); }),
                file + ":3: key 'feasibility.horizon_min': ", "must be positive");
  std::filesystem::remove(file);
}

// ElasticSettings::Stagnation's two rules each read their own four keys.
TEST(Settings, TheStagnationRulesReadTheirOwnKeys) {
  Settings s = Settings::load(default_settings_path());
  for (const char* assignment :
       {"elastic.stagnation.after=11", "elastic.stagnation.window=12",
        "elastic.stagnation.level=0.25", "elastic.stagnation.decrease=0.125",
        "elastic.stagnation.late.after=21", "elastic.stagnation.late.window=22",
        "elastic.stagnation.late.level=0.5", "elastic.stagnation.late.decrease=0.375",
        "elastic.stagnation.feasibility_after=31"})
    s.apply_override(assignment);
  const ElasticSettings::Stagnation st = elastic_settings(s).stagnation;
  EXPECT_EQ(st.first.after, 11);
  EXPECT_EQ(st.first.window, 12);
  EXPECT_EQ(st.first.level, 0.25);
  EXPECT_EQ(st.first.decrease, 0.125);
  EXPECT_EQ(st.late.after, 21);
  EXPECT_EQ(st.late.window, 22);
  EXPECT_EQ(st.late.level, 0.5);
  EXPECT_EQ(st.late.decrease, 0.375);
  EXPECT_EQ(st.feasibility_after, 31);
}

// reduction.minimize_weak homotopy relaxes the lumped row and ends by polish: with another
// formulation, or without polish, reduction_settings refuses it, naming the key.
// Both weak-minimisation keys: reduction.minimize_weak (read by reduction_settings) and
// search.refine_minimize_weak (read by screen_settings), through weak_homotopy_choice.
TEST(Settings, TheWeakHomotopyNeedsTheLumpedRowAndPolish) {
  for (const std::string key : {"reduction.minimize_weak", "search.refine_minimize_weak"}) {
    SCOPED_TRACE(key);
    const bool refine = key == "search.refine_minimize_weak";
    auto error_for = [&](std::initializer_list<std::string> overrides) {
      Settings s = Settings::load(default_settings_path());
      // The other key penalty, so only `key` can refuse.
      s.apply_override(std::string(refine ? "reduction.minimize_weak" : "search.refine_minimize_weak") + "=penalty");
      for (const std::string& o : overrides) s.apply_override(o);
      return error_of([&] {
        if (refine) screen_settings(s);
        else reduction_settings(s);
      });
    };
    const std::string homotopy = key + "=homotopy";
    const std::string penalty = key + "=penalty";
    for (const char* form : {"per_pair", "barrier"}) {
      const std::string msg = error_for({homotopy, std::string("elastic.formulation=") + form});
      EXPECT_EQ(msg, "--set: key '" + key + "': homotopy relaxes the lumped row: it needs "
                     "elastic.formulation lumped or relaxed, not " + form +
                     " (with it, set " + key + " penalty)");
    }
    const std::string polish = error_for({homotopy, "elastic.polish=false"});
    EXPECT_NE(polish.find("key '" + key + "': homotopy needs elastic.polish"), std::string::npos) << polish;
    EXPECT_NE(polish.find("(without it, set " + key + " penalty)"), std::string::npos) << polish;
    EXPECT_EQ(error_for({homotopy}), "no exception");
    EXPECT_EQ(error_for({homotopy, "elastic.formulation=relaxed"}), "no exception");
    EXPECT_EQ(error_for({"elastic.formulation=per_pair", penalty}), "no exception") << "penalty: any formulation";
    EXPECT_EQ(error_for({"elastic.formulation=barrier", penalty}), "no exception") << "penalty: any formulation";
    EXPECT_EQ(error_for({"elastic.polish=false", penalty}), "no exception") << "penalty: without polish";
    const std::string other = error_for({key + "=relaxed"});
    EXPECT_NE(other.find("key '" + key + "': must be 'penalty' or 'homotopy', got 'relaxed'"), std::string::npos)
        << other;
  }
}

}  // namespace
}  // namespace disco
