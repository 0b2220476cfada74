// disco — what a result needs to say where it came from: content hashes and the version.
//
// sha256_hex() is OpenSSL's SHA-256 of the bytes, as 64 lowercase hex digits;
// file_sha256() the same of a file's content (InputError naming the file if it cannot be
// read). disco_version() is "VERSION (git COMMIT[-dirty])": the project version from
// CMakeLists.txt and the commit of the source tree at the last build (core/util/version.cmake
// rewrites it whenever the build runs); "VERSION (git unknown)" outside a git checkout.
#pragma once

#include <string>

namespace disco {

std::string sha256_hex(const std::string& bytes);
std::string file_sha256(const std::string& path);
const char* disco_version();

}  // namespace disco
