// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The tool under signals (POSIX; plain C++, no CGAL header):
// - SIGINT or SIGTERM once stages have ended: the stages stop at their
//   next safe point, the last checked state is written, the JSON report says
//   "interrupted": true, the status is 130 or 143, and the output has no
//   more inverted elements than the input;
// - SIGKILL while the output is being written (seen in /proc/PID/fd as the
//   open temporary): the previous output file is intact and no temporary is
//   left behind.
//
// The tool, the bundled mesh and a scratch folder come from the build
// (HMO_TOOL, HMO_EXAMPLE_DATA_DIR, HMO_SCRATCH_DIR).

#include "test_util.h"

#include <dirent.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

std::string read_file(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const std::string& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// starts `args` with its standard output (and error) on a pipe; returns the
/// pid and the reading end in `fd`
pid_t spawn(const std::vector<std::string>& args, int& fd)
{
  int p[2];
  if(pipe(p) != 0) return -1;
  const pid_t pid = fork();
  if(pid == 0)
  {
    dup2(p[1], 1);
    dup2(p[1], 2);
    close(p[0]);
    close(p[1]);
    std::vector<char*> argv;
    for(const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(p[1]);
  fd = p[0];
  return pid;
}

/// the value after the n-th (0-based) occurrence of `"key": ` in `json`, or -1
long json_count(const std::string& json, const std::string& key, int n)
{
  std::size_t at = 0;
  for(int i = 0; i <= n; ++i)
  {
    at = json.find("\"" + key + "\": ", at);
    if(at == std::string::npos) return -1;
    at += key.size() + 4;
  }
  return std::atol(json.c_str() + at);
}

void test_stop_signal(const std::string& tool, const std::string& mesh, const std::string& dir, int sig,
                      int after_stages)
{
  const std::string out = dir + "/interrupted.vtk", report = dir + "/interrupted.json";
  std::remove(out.c_str());
  std::remove(report.c_str());
  int fd = -1;
  const pid_t pid = spawn({tool, mesh, out, "--report", report}, fd);
  HMO_CHECK(pid > 0);
  if(pid <= 0) return;
  // wait for `after_stages` stages to end, then signal; keep reading so that the tool
  // never blocks on a full pipe
  std::string log, line;
  bool sent = false;
  int stages_done = 0;
  char c;
  while(read(fd, &c, 1) == 1)
  {
    log += c;
    line += c;
    if(c != '\n') continue;
    if(!sent && line.find(": done in") != std::string::npos && ++stages_done == after_stages)
    {
      kill(pid, sig);
      sent = true;
    }
    line.clear();
  }
  close(fd);
  int status = 0;
  waitpid(pid, &status, 0);
  const int expected = 128 + sig;
  std::cout << (sig == SIGINT ? "SIGINT" : "SIGTERM") << ": exit status "
            << (WIFEXITED(status) ? WEXITSTATUS(status) : -1) << ", expected " << expected << std::endl;
  HMO_CHECK(sent);
  HMO_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == expected);
  HMO_CHECK(log.find("interrupted by") != std::string::npos);
  HMO_CHECK(hmo_test::file_exists(out));
  const std::string json = read_file(report);
  HMO_CHECK(json.find("\"interrupted\": true") != std::string::npos);
  const long in_inverted = json_count(json, "inverted", 0), out_inverted = json_count(json, "inverted", 1);
  std::cout << "  inverted " << in_inverted << " -> " << out_inverted << std::endl;
  HMO_CHECK(in_inverted > 0 && out_inverted >= 0 && out_inverted <= in_inverted);
}

/// an n^3 grid of unit cubes in MEDIT format
std::string grid(int n)
{
  std::ostringstream s;
  const int m = n + 1;
  s << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << m * m * m << "\n";
  for(int k = 0; k < m; ++k)
    for(int j = 0; j < m; ++j)
      for(int i = 0; i < m; ++i) s << i << ' ' << j << ' ' << k << " 0\n";
  s << "Hexahedra\n" << n * n * n << "\n";
  auto v = [m](int i, int j, int k) { return 1 + i + m * (j + m * k); };
  for(int k = 0; k < n; ++k)
    for(int j = 0; j < n; ++j)
      for(int i = 0; i < n; ++i)
        s << v(i, j, k) << ' ' << v(i + 1, j, k) << ' ' << v(i + 1, j + 1, k) << ' ' << v(i, j + 1, k) << ' '
          << v(i, j, k + 1) << ' ' << v(i + 1, j, k + 1) << ' ' << v(i + 1, j + 1, k + 1) << ' '
          << v(i, j + 1, k + 1) << " 0\n";
  s << "End\n";
  return s.str();
}

/// whether `pid` has a file open in `dir` that is a temporary (unnamed:
/// "(deleted)", or named "*.tmp")
bool writing_temporary(pid_t pid, const std::string& dir)
{
  const std::string fds = "/proc/" + std::to_string(pid) + "/fd";
  DIR* d = opendir(fds.c_str());
  if(!d) return false;
  bool found = false;
  while(dirent* e = readdir(d))
  {
    char target[4096];
    const ssize_t n = readlink((fds + "/" + e->d_name).c_str(), target, sizeof(target) - 1);
    if(n <= 0) continue;
    const std::string t(target, std::size_t(n));
    if(t.compare(0, dir.size(), dir) == 0 &&
       (t.find("(deleted)") != std::string::npos || t.find(".tmp") != std::string::npos))
      found = true;
  }
  closedir(d);
  return found;
}

std::vector<std::string> temporaries_in(const std::string& dir)
{
  std::vector<std::string> r;
  DIR* d = opendir(dir.c_str());
  if(!d) return r;
  while(dirent* e = readdir(d))
  {
    const std::string name = e->d_name;
    if(name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0) r.push_back(name);
  }
  closedir(d);
  return r;
}

void test_kill_while_writing(const std::string& tool, const std::string& dir)
{
  const std::string input = dir + "/grid.mesh", out = dir + "/killed.mesh", full = dir + "/complete.mesh";
  // 216,000 hexahedra: the writing takes a while (27,000 with the sanitized
  // tool, whose writing is as slow)
  write_file(input, grid(hmo_test::sanitized ? 30 : 60));
  // the complete output, from a run left alone
  int fd = -1;
  pid_t pid = spawn({tool, input, full, "--untangle", "--quiet"}, fd);
  char buffer[4096];
  while(read(fd, buffer, sizeof(buffer)) > 0) {}
  close(fd);
  int status = 0;
  waitpid(pid, &status, 0);
  HMO_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const std::string complete = read_file(full);
  const std::string previous = "the previous output, which a killed run must leave intact\n";

  int landed = 0, trials = 0;
  for(; trials < 40 && landed < 3; ++trials)
  {
    write_file(out, previous);
    pid = spawn({tool, input, out, "--untangle", "--quiet"}, fd);
    std::thread drain([fd] {
      char b[4096];
      while(read(fd, b, sizeof(b)) > 0) {}
    });
    bool killed_while_writing = false;
    for(;;)
    {
      if(waitpid(pid, &status, WNOHANG) == pid) break;
      if(writing_temporary(pid, dir))
      {
        kill(pid, SIGKILL);
        killed_while_writing = true;
        waitpid(pid, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    drain.join();
    close(fd);
    const std::string now = read_file(out);
    const std::vector<std::string> left = temporaries_in(dir);
    HMO_CHECK(now == previous || now == complete);
    HMO_CHECK(left.empty());
    for(const std::string& t : left) std::cerr << "temporary left behind: " << t << std::endl;
    if(killed_while_writing)
    {
      HMO_CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
      ++landed;
      std::cout << "SIGKILL while writing: the previous output is "
                << (now == previous ? "intact" : "replaced by the complete one (the kill came after the rename)")
                << ", " << left.size() << " temporaries left" << std::endl;
    }
  }
  std::cout << landed << " kills landed while writing, in " << trials << " runs" << std::endl;
  HMO_CHECK(landed > 0);
  std::remove(input.c_str());
  std::remove(out.c_str());
  std::remove(full.c_str());
}

} // namespace

int main(int, char** argv)
{
  const std::string tool = HMO_TOOL, mesh = std::string(HMO_EXAMPLE_DATA_DIR) + "/bunny_dualsheet.vtk",
                    dir = HMO_SCRATCH_DIR;
  mkdir(dir.c_str(), 0755);
  test_stop_signal(tool, mesh, dir, SIGINT, 2);  // after the untangling's main stage
  test_stop_signal(tool, mesh, dir, SIGTERM, 1);
  test_kill_while_writing(tool, dir);
  return hmo_test::report(argv[0]);
}
