#pragma once
// SHA-256 through OpenSSL: the validator's pixel checksums (validate Checksums) and the batch
// runner's input and output checksums (batch BatchInputs, BatchRun) hash with it, so the digest,
// its hex form and the folder rule are written once. OpenSSL stays inside Sha256.cpp.
#include <cstddef>
#include <filesystem>
#include <string>

struct evp_md_ctx_st;  // OpenSSL's EVP_MD_CTX

namespace mvw::process {

class Sha256 {
 public:
  // Throws mvw::Error when OpenSSL has no SHA-256.
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;

  void add(const void* bytes, std::size_t size);
  // A file's bytes. Throws InputError naming the file when it cannot be read; `role` (when not
  // empty) says what the file was to the caller: "cannot be read (ROLE)".
  void addFile(const std::filesystem::path& file, const std::string& role = "");
  // Finishes the digest: lower-case hex.
  std::string hex();

 private:
  evp_md_ctx_st* ctx_ = nullptr;
};

// SHA-256 of a file's bytes, lower-case hex. Throws InputError as Sha256::addFile does.
std::string fileSha256(const std::filesystem::path& file, const std::string& role = "");

// A file as fileSha256; a folder (a DICOM series) as the names (relative, '/'-separated, each
// with its terminating NUL) and bytes of every regular file in it and below, in name order.
std::string pathSha256(const std::filesystem::path& path, const std::string& role = "");

}  // namespace mvw::process
