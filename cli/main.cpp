// SPDX-License-Identifier: GPL-3.0-or-later
// The constrict command line: parse arguments, call the library, write results. No geometry here.
#include <CLI/CLI.hpp>

#include <sys/mman.h>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "constrict/memory.hpp"
#include "constrict/status.hpp"
#include "constrict/version.hpp"

namespace {

// Transparent huge pages for the large arrays (the Delaunay simplices, the engines' per-simplex
// state): each of their pages is touched once, and the kernel's page faults were a fifth of a 10^6
// run (docs/benchmarks.md, "Huge pages"). Where the kernel gives huge pages only on request
// (transparent_hugepage "madvise", Debian's default), glibc requests them when its tunable
// glibc.malloc.hugetlb=1 is set at program start: the CLI runs itself again once with it. Outputs
// are unchanged. Not done when the user set the tunable (any value), under valgrind (whose child
// would run unchecked), or when huge_pages_enabled() is false (CONSTRICT_NO_HUGEPAGES set, or a
// VM that hands free memory back to its host, where huge pages cost more than they save).
void reexec_with_huge_pages(char** argv) {
  if (!constrict::huge_pages_enabled()) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables && std::strstr(tunables, "glibc.malloc.hugetlb")) return;
  if (const char* pre = std::getenv("LD_PRELOAD"); pre && std::strstr(pre, "vgpreload")) return;
  std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!std::getline(mode, line) || line.find("[madvise]") == std::string::npos) return;
  const std::string value = tunables && *tunables ? std::string(tunables) + ":glibc.malloc.hugetlb=1" : "glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);  // returns only on failure: go on as we are
  unsetenv("GLIBC_TUNABLES");
  if (tunables) setenv("GLIBC_TUNABLES", tunables, 1);
}

// The largest blocks straight from the kernel and back (glibc's mmap threshold fixed at 16 MiB):
// by default glibc raises that threshold to the size of each large block freed (up to 32 MiB),
// and the engines' arrays of 16 to 32 MiB, freed between stages, then come from and go back to
// its heap, where the next stage's arrays could not reuse the holes: the process kept the pages.
// Peak memory at 10^6 points (docs/benchmarks.md): noisy curve 308 -> 253 MiB, uniform square
// 274 -> 256, smooth curve 262 -> 253; the time the same within the noise (4 MiB also lowered
// the 3D peaks, but cost the 2D runs 1-4 %). A process-wide policy, so the CLI sets it, not the
// library.
void fix_mmap_threshold() {
#if defined(__GLIBC__) && defined(M_MMAP_THRESHOLD)
  if (const char* tunables = std::getenv("GLIBC_TUNABLES"); tunables && std::strstr(tunables, "mmap_threshold")) return;
  (void)mallopt(M_MMAP_THRESHOLD, 16 << 20);
#endif
}

// The heap's top faulted in on the idle core. A first touch of fresh memory is a page fault, and
// on a VM that hands free memory back to its host it costs the most: about 5 % of CGAL's 3D
// insertion on the 10^6 star (docs/benchmarks.md, "The heap's top faulted in beside"), which runs
// on one core while the other waits. Blocks below the mmap threshold (CGAL's cells and vertices,
// most vectors) come from glibc's heap, which grows by moving the program break; with a top pad of
// 8 MiB every move reaches that far ahead of the allocation that asked for it. A thread watches
// the break and has the kernel fault in the pages below it (MADV_POPULATE_WRITE, Linux 5.14:
// zero pages, as a first write would give; nothing reads or writes them), so that the allocating
// thread finds them present. Outputs are unchanged; the peak grows by at most the pad. Not done
// when CONSTRICT_NO_PREFAULT is set, when the user set glibc's top pad, under valgrind, or where
// the kernel declines the call (the thread then ends).
class HeapTopPrefault {
 public:
  HeapTopPrefault() {
#if defined(__linux__) && defined(__GLIBC__) && defined(M_TOP_PAD)
    if (std::getenv("CONSTRICT_NO_PREFAULT")) return;
    if (const char* t = std::getenv("GLIBC_TUNABLES"); t && std::strstr(t, "top_pad")) return;
    if (const char* pre = std::getenv("LD_PRELOAD"); pre && std::strstr(pre, "vgpreload")) return;
    if (mallopt(M_TOP_PAD, kPad) != 1) return;
    try {
      thread_ = std::thread([this] { run(); });
    } catch (...) {  // no thread: go on without
    }
#endif
  }
  HeapTopPrefault(const HeapTopPrefault&) = delete;
  HeapTopPrefault& operator=(const HeapTopPrefault&) = delete;
  ~HeapTopPrefault() {
    if (!thread_.joinable()) return;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }

 private:
  static constexpr int kPad = 8 << 20;
  static constexpr int kDefaultPad = 128 << 10;  // glibc's (mallopt(3))
  static constexpr int kPopulateWrite = 23;  // MADV_POPULATE_WRITE (older headers lack the name)

  void run() {
    const long page = sysconf(_SC_PAGESIZE);
    const std::uintptr_t mask = ~static_cast<std::uintptr_t>(page > 0 ? page - 1 : 4095);
    const auto program_break = [mask] { return reinterpret_cast<std::uintptr_t>(sbrk(0)) & mask; };
    std::uintptr_t done = program_break();
    auto idle = std::chrono::microseconds(250);
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
      const std::uintptr_t top = program_break();
      if (top > done) {
        if (madvise(reinterpret_cast<void*>(done), top - done, kPopulateWrite) != 0 && errno == EINVAL) {
          (void)mallopt(M_TOP_PAD, kDefaultPad);  // a kernel before 5.14: glibc's default back
          return;
        }
        idle = std::chrono::microseconds(250);
      } else {
        idle = std::min(2 * idle, std::chrono::microseconds(4000));  // the heap is still: look less often
      }
      done = top;  // also after a trim, which lowers the break
      wake_.wait_for(lock, idle, [this] { return stop_; });
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;  // guarded by mutex_
  std::thread thread_;
};

}  // namespace

int main(int argc, char** argv) {
  reexec_with_huge_pages(argv);
  // A reader that closes its end of a pipe early (`constrict ... | head -0`) makes the next write
  // to it fail with EPIPE, reported below as a failed write (exit 4), instead of killing the
  // process with SIGPIPE (exit 141, like a crash; the result files are written by then).
  (void)std::signal(SIGPIPE, SIG_IGN);
  fix_mmap_threshold();
  HeapTopPrefault prefault;  // before any large allocation; ends when main returns
  using namespace constrict;
  CLI::App app{"constrict " CONSTRICT_VERSION_STRING
               " - object reconstruction with the gamma-neighborhood graph (Veltkamp)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("constrict ") + CONSTRICT_VERSION_STRING);
  const std::vector<cli::Command> commands = {cli::add_reconstruct_command(app), cli::add_graph_command(app),
                                             cli::add_compare_command(app), cli::add_render_command(app)};

  // A mistyped command word (`constrict grph ...`) met CLI11's "A subcommand is required": name it.
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    for (const auto& c : commands) known = known || c.app->check_name(argv[1]);
    if (!known) {
      std::fprintf(stderr,
                   "constrict: error [InvalidArgument]: unknown command '%s': use reconstruct, graph, compare or render "
                   "(see constrict --help)\n",
                   argv[1]);
      return exit_code(StatusCode::InvalidArgument);
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "constrict: error [InvalidArgument]: %s (see constrict --help)\n", e.what());
    return exit_code(StatusCode::InvalidArgument);
  }
  try {
    for (const auto& c : commands)
      if (c.app->parsed()) {
        const int rc = c.run();
        // What went to standard output (compare's verdict, the summary lines) is part of the
        // result: a full disk or a closed stream there is a failed write, not success.
        errno = 0;  // (set by the flush when it fails; an earlier failed write leaves only ferror)
        if (rc == 0 && (std::fflush(stdout) != 0 || std::ferror(stdout) != 0)) {
          std::fprintf(stderr, "constrict: error [WriteFailed]: writing to standard output failed%s\n",
                       errno == EPIPE ? " (the reader closed the pipe)" : "");
          return exit_code(StatusCode::WriteFailed);
        }
        return rc;
      }
  } catch (const InternalError& e) {
    std::fprintf(stderr, "constrict: internal error (please report): %s\n", e.what());
    return exit_code(StatusCode::Internal);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "constrict: error [Unsupported]: out of memory\n");
    return exit_code(StatusCode::Unsupported);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "constrict: internal error (please report): %s\n", e.what());
    return exit_code(StatusCode::Internal);
  }
  return 0;
}
