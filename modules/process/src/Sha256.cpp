#include "mvw/process/Sha256.h"

#include <openssl/evp.h>

#include <algorithm>
#include <fstream>
#include <vector>

#include "mvw/core/Error.h"

namespace mvw::process {

namespace fs = std::filesystem;

Sha256::Sha256() : ctx_(EVP_MD_CTX_new()) {
  if (!ctx_ || EVP_DigestInit_ex(ctx_, EVP_sha256(), nullptr) != 1) {
    EVP_MD_CTX_free(ctx_);
    throw Error("SHA-256 is not available from OpenSSL");
  }
}

Sha256::~Sha256() { EVP_MD_CTX_free(ctx_); }

void Sha256::add(const void* bytes, std::size_t size) { EVP_DigestUpdate(ctx_, bytes, size); }

void Sha256::addFile(const fs::path& file, const std::string& role) {
  const std::string why = role.empty() ? "cannot be read" : "cannot be read (" + role + ")";
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, why);
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    add(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InputError(file, why);
}

std::string Sha256::hex() {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned n = 0;
  EVP_DigestFinal_ex(ctx_, digest, &n);
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned i = 0; i < n; ++i) {
    out += digits[digest[i] >> 4];
    out += digits[digest[i] & 15];
  }
  return out;
}

std::string fileSha256(const fs::path& file, const std::string& role) {
  Sha256 sha;
  sha.addFile(file, role);
  return sha.hex();
}

std::string pathSha256(const fs::path& path, const std::string& role) {
  if (!fs::is_directory(path)) return fileSha256(path, role);
  Sha256 sha;
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(path))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    const std::string name = f.lexically_relative(path).generic_string();
    sha.add(name.data(), name.size() + 1);
    sha.addFile(f, role);
  }
  return sha.hex();
}

}  // namespace mvw::process
