// The manifest of a search directory and the rules for writing into one
// (search/run_manifest.h), and the "did you mean" of mistyped words (core/util/suggest.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/util/errors.h"
#include "core/util/provenance.h"
#include "core/util/suggest.h"
#include "search/run_manifest.h"

namespace disco {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const std::string kAxis = std::string(DISCO_SOURCE_DIR) + "/configs/scenarios/one_robot_axis.yaml";

json manifest_of(const std::vector<std::string>& sets, std::uint64_t seed = 7) {
  std::vector<std::string> scene_sets, settings_sets;
  split_overrides(sets, scene_sets, settings_sets);
  Settings settings = Settings::load(default_settings_path());
  for (const auto& s : settings_sets) settings.apply_override(s);
  const SearchPlan plan = load_search_plan({kAxis}, 2, 1, scene_sets);
  return search_manifest(plan, settings, {{kAxis}, sets, seed, 2, 0.0, false});
}

std::string fresh_dir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/run_manifest_" + name;
  fs::remove_all(dir);
  return dir;
}

std::string error_of(const std::string& dir, OutDirMode mode, const json& m) {
  try {
    prepare_out_dir(dir, mode, m);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RunManifest, RecordsTheInputsWithTheirHashes) {
  const json m = manifest_of({"scene.steps=20", "elastic.zeta=20"});
  EXPECT_EQ(m.at("seed"), 7);
  EXPECT_EQ(m.at("version"), disco_version());
  EXPECT_EQ(m.at("scenes")[0].at("sha256"), file_sha256(kAxis));
  EXPECT_EQ(m.at("scenes")[0].at("overrides"), json::array({"steps=20"}));
  EXPECT_EQ(m.at("settings").at("values").at("elastic.zeta"), "20");
  EXPECT_EQ(m.at("overrides"), json::array({"scene.steps=20", "elastic.zeta=20"}));
}

TEST(RunManifest, TheSameCommandMatchesAndEachDifferenceIsNamed) {
  const json base = manifest_of({"scene.steps=20"});
  EXPECT_TRUE(manifest_differences(base, manifest_of({"scene.steps=20"})).empty());
  // A number written another way is the same setting.
  EXPECT_TRUE(manifest_differences(base, manifest_of({"scene.steps=20", "elastic.zeta=1e1"})).empty());
  const auto d = manifest_differences(base, manifest_of({"scene.steps=12", "elastic.zeta=20"}, 8));
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[0], "seed: 7 there, 8 here");
  EXPECT_EQ(d[1], "scene 'one_robot_axis': overrides [steps=20] there, [steps=12] here");
  EXPECT_EQ(d[2], "setting elastic.zeta: 10.0 there, 20 here");
  json other = base;
  other["scenes"][0]["sha256"] = std::string(64, '0');
  const auto changed = manifest_differences(other, base);
  ASSERT_EQ(changed.size(), 1u);
  EXPECT_NE(changed[0].find("scene 'one_robot_axis': file content differs"), std::string::npos);
  EXPECT_EQ(manifest_differences(json::object(), base).at(0),
            "the earlier manifest is not a disco search manifest");
}

TEST(RunManifest, ANonEmptyDirectoryIsRefusedWithoutResumeAndForceRemovesOnlyDiscosFiles) {
  const std::string dir = fresh_dir("fresh");
  const json m = manifest_of({});
  EXPECT_EQ(prepare_out_dir(dir, OutDirMode::kFresh, m), 0);
  EXPECT_TRUE(fs::is_directory(dir + "/best"));
  EXPECT_EQ(json::parse(std::ifstream(dir + "/manifest.json")), m);
  std::ofstream(dir + "/runs.jsonl") << "{}\n";
  std::ofstream(dir + "/notes.txt") << "mine\n";
  const std::string e = error_of(dir, OutDirMode::kFresh, m);
  EXPECT_NE(e.find("the directory is not empty (it holds best, manifest.json, notes.txt, runs.jsonl)"),
            std::string::npos) << e;
  EXPECT_TRUE(fs::exists(dir + "/runs.jsonl"));
  EXPECT_EQ(prepare_out_dir(dir, OutDirMode::kForce, m), 0);
  EXPECT_FALSE(fs::exists(dir + "/runs.jsonl"));
  EXPECT_TRUE(fs::exists(dir + "/notes.txt"));  // not disco's: kept
}

TEST(RunManifest, ResumeAppendsItsInvocationOrRefusesAMismatchOrAMissingManifest) {
  const std::string dir = fresh_dir("resume");
  EXPECT_EQ(prepare_out_dir(dir, OutDirMode::kResume, manifest_of({})), 0);  // nothing yet
  EXPECT_EQ(prepare_out_dir(dir, OutDirMode::kResume, manifest_of({})), 1);
  EXPECT_EQ(json::parse(std::ifstream(dir + "/manifest.json")).at("invocations").size(), 2u);
  const std::string e = error_of(dir, OutDirMode::kResume, manifest_of({"scene.steps=12"}));
  EXPECT_NE(e.find("holds a different run"), std::string::npos) << e;
  EXPECT_NE(e.find("overrides [] there, [steps=12] here"), std::string::npos) << e;
  fs::remove(dir + "/manifest.json");
  std::ofstream(dir + "/runs.jsonl") << "{}\n";
  EXPECT_NE(error_of(dir, OutDirMode::kResume, manifest_of({})).find("manifest.json is missing"),
            std::string::npos);
}

TEST(Suggest, NamesTheClosestCandidatesNearestFirst) {
  const std::vector<std::string> commands = {"solve", "search"};
  EXPECT_EQ(did_you_mean("sovle", commands), " (did you mean 'solve'?)");
  EXPECT_EQ(did_you_mean("serach", commands), " (did you mean 'search'?)");
  EXPECT_EQ(did_you_mean("plot", commands), "");
  const std::vector<std::string> keys = {"elastic.zeta", "elastic.zeta_max", "ipopt.tol"};
  EXPECT_EQ(closest("zeta_max", keys), std::vector<std::string>{"elastic.zeta_max"});
  EXPECT_EQ(closest("elastic.zeta_mx", keys),
            (std::vector<std::string>{"elastic.zeta_max", "elastic.zeta"}));
  EXPECT_TRUE(closest("elastic.zeta", keys).size() == 1u);  // itself is not suggested
}

}  // namespace
}  // namespace disco
