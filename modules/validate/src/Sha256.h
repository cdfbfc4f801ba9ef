#pragma once
// SHA-256 through OpenSSL for the validator's pixel checksums (Checksums.cpp) and the batch
// runner's file checksums (BatchRun.cpp): a digest started, and finished as lower-case hex.
#include <openssl/evp.h>

#include <memory>
#include <string>

#include "mvw/core/Error.h"

namespace mvw::validate::detail {

using Sha256 = std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)>;

inline Sha256 newSha256() {
  Sha256 ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
    throw Error("SHA-256 is not available from OpenSSL");
  return ctx;
}

// Finishes the digest; lower-case hex.
inline std::string hexDigest(Sha256& ctx) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned n = 0;
  EVP_DigestFinal_ex(ctx.get(), digest, &n);
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned i = 0; i < n; ++i) {
    out += digits[digest[i] >> 4];
    out += digits[digest[i] & 15];
  }
  return out;
}

}  // namespace mvw::validate::detail
