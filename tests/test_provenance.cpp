// Content hashes, the version string, and the settings text behind the settings hash
// (core/util/provenance.h, Settings::canonical_text).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <string>

#include "core/config/settings.h"
#include "core/util/errors.h"
#include "core/util/provenance.h"

namespace disco {
namespace {

// FIPS 180-2, appendix B: the SHA-256 test vectors.
TEST(Provenance, Sha256MatchesTheStandardTestVectors) {
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Provenance, FileHashIsTheHashOfItsBytesAndAMissingFileIsAnInputError) {
  const std::string path = ::testing::TempDir() + "/provenance_abc.txt";
  std::ofstream(path, std::ios::binary) << "abc";
  EXPECT_EQ(file_sha256(path), sha256_hex("abc"));
  std::remove(path.c_str());
  try {
    file_sha256(path);
    FAIL() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(Provenance, VersionNamesTheProjectVersionAndTheCommit) {
  EXPECT_TRUE(std::regex_match(disco_version(),
                               std::regex(R"(\d+\.\d+\.\d+ \(git ([0-9a-f]{7,}(-dirty)?|unknown)\))")))
      << disco_version();
}

TEST(Provenance, SettingsTextIgnoresCommentsAndLayoutButNotValues) {
  const Settings a = Settings::parse("elastic:\n  zeta: 10   # a comment\nipopt:\n  tol: 1e-8\n", "a");
  const Settings b = Settings::parse("# header\nelastic: {zeta: 10}\nipopt:\n    tol: 1e-8\n", "b");
  EXPECT_EQ(a.canonical_text(), b.canonical_text());
  Settings c = a;
  c.apply_override("elastic.zeta=20");
  EXPECT_NE(c.canonical_text(), a.canonical_text());
  c.apply_override("elastic.zeta=10");
  EXPECT_EQ(c.canonical_text(), a.canonical_text());
}

}  // namespace
}  // namespace disco
