// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// All rights reserved.
//
// This file is part of CGAL (www.cgal.org)
//
// $URL$
// $Id$
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : Hexahedral_mesh_optimization contributors

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_ATOMIC_OUTPUT_FILE_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_ATOMIC_OUTPUT_FILE_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// An output file that appears complete or not at all: the data goes to a
// temporary file in the target's directory, which is renamed over the target
// by commit(). If commit() is not reached (error, exception), the destructor
// removes the temporary and the target is left as it was.
//
// On Linux the temporary is first an unnamed file (O_TMPFILE): it gets a
// name (linkat through /proc/self/fd) only once its data is written and
// synced, just before the rename. A process killed while writing (SIGKILL,
// power loss after the sync) then leaves no temporary behind, only the
// target as it was; the window where a named temporary exists is the
// link-and-rename. Where O_TMPFILE or /proc is missing, the temporary is
// named from the start, as elsewhere.

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
#if defined(__linux__)
#include <fcntl.h>
#if defined(O_TMPFILE)
#define CGAL_HMO_IO_HAVE_TMPFILE 1
#endif
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
#ifdef CGAL_HMO_IO_HAVE_TMPFILE
    {
      const std::filesystem::path parent = std::filesystem::path(target).parent_path();
      const int fd = ::open(parent.empty() ? "." : parent.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
      if(fd >= 0)
      {
        file_ = ::fdopen(fd, "wb");
        if(file_ != nullptr)
        {
          unnamed_ = true;
          return true;
        }
        ::close(fd);
      }
    }
#endif
    return open_named(error);
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
    if(!failed_ && unnamed_ && !give_name())
    {
      error = std::string("cannot name the temporary file: ") + std::strerror(errno_);
      discard();
      return false;
    }
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
    unnamed_ = false;
    failed_ = false;
    errno_ = 0;
  }

private:
  /// a fresh name next to the target
  std::string next_temp_name()
  {
    static std::atomic<unsigned long> counter(0);
    const unsigned long long stamp = static_cast<unsigned long long>(
      std::chrono::steady_clock::now().time_since_epoch().count());
    return target_ + "." + std::to_string((stamp + 7919ull * counter++) % 1000000007ull) + ".tmp";
  }

#ifdef CGAL_HMO_IO_HAVE_TMPFILE
  /// links the unnamed temporary to a fresh name (sets `temp_`); false with
  /// `errno_` set on failure
  bool give_name()
  {
    const std::string self = "/proc/self/fd/" + std::to_string(::fileno(file_));
    for(int attempt = 0; attempt < 100; ++attempt)
    {
      const std::string name = next_temp_name();
      if(::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0)
      {
        temp_ = name;
        unnamed_ = false;
        return true;
      }
      if(errno != EEXIST) break;
    }
    errno_ = errno;
    failed_ = true;
    return false;
  }
#else
  bool give_name() { return true; }
#endif

  bool open_named(std::string& error)
  {
    for(int attempt = 0; attempt < 100; ++attempt)
    {
      temp_ = next_temp_name();
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


  std::string target_;
  bool unnamed_ = false;
  std::string temp_;
  std::FILE* file_ = nullptr;
  bool failed_ = false;
  int errno_ = 0;
};

/// Whether a file can be written at `target`, to find out before the work
/// that produces its data rather than after: its folder exists, `target` is
/// not a folder (the final rename would fail), and the temporary that
/// Atomic_output_file writes can be created next to it. That temporary is
/// created and removed at once (on Linux it is unnamed, so nothing ever
/// appears in the folder). On failure `error` says why.
inline bool probe_output_file(const std::string& target, std::string& error)
{
  namespace fs = std::filesystem;
  if(target.empty())
  {
    error = "empty file name";
    return false;
  }
  const fs::path parent = fs::path(target).parent_path();
  const fs::path folder = parent.empty() ? fs::path(".") : parent;
  std::error_code ec;
  const fs::file_status folder_status = fs::status(folder, ec);
  if(ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory)
  {
    error = "cannot access its folder '" + folder.string() + "': " + ec.message();
    return false;
  }
  if(!fs::exists(folder_status))
  {
    error = "its folder '" + folder.string() + "' does not exist";
    return false;
  }
  if(!fs::is_directory(folder_status))
  {
    error = "'" + folder.string() + "' is not a folder";
    return false;
  }
  if(fs::is_directory(fs::status(target, ec)))
  {
    error = "is a folder, not a file";
    return false;
  }
  Atomic_output_file probe;
  if(!probe.open(target, error))
    return false;
  probe.discard();
  return true;
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_ATOMIC_OUTPUT_FILE_H
