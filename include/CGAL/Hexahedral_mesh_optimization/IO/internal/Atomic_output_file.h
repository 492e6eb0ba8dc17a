// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_ATOMIC_OUTPUT_FILE_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_ATOMIC_OUTPUT_FILE_H

// An output file that appears complete or not at all: the data goes to a
// temporary file in the target's directory, which is renamed over the target
// by commit(). If commit() is not reached (error, exception), the destructor
// removes the temporary and the target is left as it was.

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#define CGAL_HMO_IO_HAVE_FSYNC 1
#endif

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

class Atomic_output_file
{
public:
  Atomic_output_file() = default;
  Atomic_output_file(const Atomic_output_file&) = delete;
  Atomic_output_file& operator=(const Atomic_output_file&) = delete;

  ~Atomic_output_file() { discard(); }

  /// creates the temporary file next to `target`; on failure `error` says why
  bool open(const std::string& target, std::string& error)
  {
    discard();
    target_ = target;
    static std::atomic<unsigned long> counter(0);
    const unsigned long long stamp = static_cast<unsigned long long>(
      std::chrono::steady_clock::now().time_since_epoch().count());
    for(int attempt = 0; attempt < 100; ++attempt)
    {
      temp_ = target + "." + std::to_string((stamp + 7919ull * counter++) % 1000000007ull) + ".tmp";
      errno = 0;
      // "x": fails if the name exists, so a concurrent writer is never clobbered
      file_ = std::fopen(temp_.c_str(), "wbx");
      if(file_ != nullptr)
        return true;
      if(errno != EEXIST)
        break;
    }
    error = std::string("cannot create a temporary file next to the target: ") +
            (errno != 0 ? std::strerror(errno) : "unknown error");
    temp_.clear();
    return false;
  }

  bool write(const char* data, std::size_t n)
  {
    if(file_ == nullptr || failed_)
      return false;
    if(n != 0 && std::fwrite(data, 1, n, file_) != n)
    {
      failed_ = true;
      errno_ = errno;
    }
    return !failed_;
  }

  /// flushes, closes and renames the temporary over the target
  bool commit(std::string& error)
  {
    if(file_ == nullptr)
    {
      error = "no file open";
      return false;
    }
    if(!failed_ && std::fflush(file_) != 0)
    {
      failed_ = true;
      errno_ = errno;
    }
#ifdef CGAL_HMO_IO_HAVE_FSYNC
    if(!failed_ && ::fsync(::fileno(file_)) != 0)
    {
      failed_ = true;
      errno_ = errno;
    }
#endif
    const int closed = std::fclose(file_);
    file_ = nullptr;
    if(!failed_ && closed != 0)
    {
      failed_ = true;
      errno_ = errno;
    }
    if(failed_)
    {
      error = std::string("write error: ") + (errno_ != 0 ? std::strerror(errno_) : "unknown error");
      discard();
      return false;
    }
    std::error_code ec;
    std::filesystem::rename(temp_, target_, ec);  // replaces an existing target
    if(ec)
    {
      error = "cannot replace the target: " + ec.message();
      discard();
      return false;
    }
    temp_.clear();
    return true;
  }

  /// closes and removes the temporary, if any
  void discard()
  {
    if(file_ != nullptr)
    {
      std::fclose(file_);
      file_ = nullptr;
    }
    if(!temp_.empty())
    {
      std::remove(temp_.c_str());
      temp_.clear();
    }
    failed_ = false;
    errno_ = 0;
  }

private:
  std::string target_;
  std::string temp_;
  std::FILE* file_ = nullptr;
  bool failed_ = false;
  int errno_ = 0;
};

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_ATOMIC_OUTPUT_FILE_H
