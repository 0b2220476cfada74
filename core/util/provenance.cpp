#include "core/util/provenance.h"

#include <openssl/evp.h>

#include <fstream>
#include <sstream>

#include "core/util/check.h"
#include "core/util/errors.h"
#include "disco_version.h"  // generated in the build tree by core/util/version.cmake

namespace disco {

std::string sha256_hex(const std::string& bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  const int ok = EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha256(), nullptr);
  DISCO_CHECK(ok == 1 && length == 32, "EVP_Digest(SHA-256)");
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned int k = 0; k < length; ++k) {
    out += hex[digest[k] >> 4];
    out += hex[digest[k] & 15];
  }
  return out;
}

std::string file_sha256(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open for reading");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return sha256_hex(bytes.str());
}

const char* disco_version() { return DISCO_VERSION_STRING; }

}  // namespace disco
