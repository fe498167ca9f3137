// content_hash: FNV-1a 64 against the published test vectors, file = bytes, and failures.
#include "common/error.hpp"
#include "common/h5/content_hash.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace aniso::h5 {
namespace {

std::string temporary(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))).string();
}

TEST(ContentHash, MatchesFnv1a64TestVectors) {
  // Test vectors of the FNV reference implementation (Noll's fnv test suite).
  EXPECT_EQ(content_hash_of_bytes(""), "cbf29ce484222325");
  EXPECT_EQ(content_hash_of_bytes("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(content_hash_of_bytes("foobar"), "85944171f73967e8");
}

TEST(ContentHash, OfAFileIsTheHashOfItsBytesAcrossBufferBoundaries) {
  const std::string path = temporary("content_hash");
  std::string bytes;
  for (int k = 0; k < 200000; ++k)
    bytes.push_back(static_cast<char>((k * 7919) % 251));
  {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
  }
  EXPECT_EQ(content_hash(path), content_hash_of_bytes(bytes));
  bytes[123456] ^= 1; // one flipped bit changes the hash
  EXPECT_NE(content_hash(path), content_hash_of_bytes(bytes));
  std::filesystem::remove(path);
}

TEST(ContentHash, MissingFileIsAFileErrorNamingIt) {
  try {
    static_cast<void>(content_hash("/nonexistent/probe.h5"));
    FAIL() << "expected FileError";
  } catch (const FileError& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/probe.h5"), std::string::npos);
  }
}

} // namespace
} // namespace aniso::h5
