// The reader reads a live session as one snapshot: a commit by the recorder between two of
// the reader's queries must not show in the second and not the first. A VFS shim makes the
// commit happen exactly there, when the reader's connection first ends a read transaction.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>

#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_writer.hpp"
#include "session_test_support.hpp"

namespace palpa::session {
namespace {

// A pass-through VFS over the default one; `hook` runs once, right after a connection
// opened through it releases a WAL read lock (the end of a read transaction).
struct ShimFile {
  sqlite3_file base;
  sqlite3_file* real;
};
sqlite3_vfs* g_real = nullptr;
std::function<void()> g_hook;

sqlite3_file* real(sqlite3_file* f) { return reinterpret_cast<ShimFile*>(f)->real; }
int shim_close(sqlite3_file* f) { return real(f)->pMethods->xClose(real(f)); }
int shim_read(sqlite3_file* f, void* p, int n, sqlite3_int64 o) { return real(f)->pMethods->xRead(real(f), p, n, o); }
int shim_write(sqlite3_file* f, const void* p, int n, sqlite3_int64 o) {
  return real(f)->pMethods->xWrite(real(f), p, n, o);
}
int shim_truncate(sqlite3_file* f, sqlite3_int64 n) { return real(f)->pMethods->xTruncate(real(f), n); }
int shim_sync(sqlite3_file* f, int flags) { return real(f)->pMethods->xSync(real(f), flags); }
int shim_size(sqlite3_file* f, sqlite3_int64* n) { return real(f)->pMethods->xFileSize(real(f), n); }
int shim_lock(sqlite3_file* f, int l) { return real(f)->pMethods->xLock(real(f), l); }
int shim_unlock(sqlite3_file* f, int l) { return real(f)->pMethods->xUnlock(real(f), l); }
int shim_check(sqlite3_file* f, int* out) { return real(f)->pMethods->xCheckReservedLock(real(f), out); }
int shim_control(sqlite3_file* f, int op, void* arg) { return real(f)->pMethods->xFileControl(real(f), op, arg); }
int shim_sector(sqlite3_file* f) { return real(f)->pMethods->xSectorSize(real(f)); }
int shim_device(sqlite3_file* f) { return real(f)->pMethods->xDeviceCharacteristics(real(f)); }
int shim_shm_map(sqlite3_file* f, int i, int size, int extend, void volatile** p) {
  return real(f)->pMethods->xShmMap(real(f), i, size, extend, p);
}
int shim_shm_lock(sqlite3_file* f, int offset, int n, int flags) {
  const int rc = real(f)->pMethods->xShmLock(real(f), offset, n, flags);
  // Offsets 3 to 7 are the WAL read marks.
  if (rc == SQLITE_OK && flags == (SQLITE_SHM_UNLOCK | SQLITE_SHM_SHARED) && offset >= 3 && g_hook) {
    auto hook = std::move(g_hook);
    g_hook = nullptr;
    hook();
  }
  return rc;
}
void shim_shm_barrier(sqlite3_file* f) { real(f)->pMethods->xShmBarrier(real(f)); }
int shim_shm_unmap(sqlite3_file* f, int del) { return real(f)->pMethods->xShmUnmap(real(f), del); }

const sqlite3_io_methods kShimMethods = {2,           shim_close,     shim_read,       shim_write,     shim_truncate,
                                         shim_sync,   shim_size,      shim_lock,       shim_unlock,    shim_check,
                                         shim_control, shim_sector,   shim_device,     shim_shm_map,   shim_shm_lock,
                                         shim_shm_barrier, shim_shm_unmap, nullptr,     nullptr};

int shim_open(sqlite3_vfs*, sqlite3_filename name, sqlite3_file* f, int flags, int* out_flags) {
  auto* shim = reinterpret_cast<ShimFile*>(f);
  shim->real = reinterpret_cast<sqlite3_file*>(shim + 1);
  const int rc = g_real->xOpen(g_real, name, shim->real, flags, out_flags);
  shim->base.pMethods = shim->real->pMethods != nullptr ? &kShimMethods : nullptr;
  return rc;
}

class ShimVfs {
 public:
  ShimVfs() {
    g_real = sqlite3_vfs_find(nullptr);
    vfs_ = *g_real;
    vfs_.iVersion = 1;  // the calls below forward to the real VFS's version-1 methods
    vfs_.szOsFile = static_cast<int>(sizeof(ShimFile)) + g_real->szOsFile;
    vfs_.zName = "palpa-snapshot-shim";
    vfs_.pAppData = nullptr;
    vfs_.xOpen = shim_open;
    vfs_.xDelete = [](sqlite3_vfs*, const char* n, int s) { return g_real->xDelete(g_real, n, s); };
    vfs_.xAccess = [](sqlite3_vfs*, const char* n, int f, int* o) { return g_real->xAccess(g_real, n, f, o); };
    vfs_.xFullPathname = [](sqlite3_vfs*, const char* n, int k, char* o) {
      return g_real->xFullPathname(g_real, n, k, o);
    };
    vfs_.xDlOpen = [](sqlite3_vfs*, const char* n) { return g_real->xDlOpen(g_real, n); };
    vfs_.xDlError = [](sqlite3_vfs*, int n, char* o) { g_real->xDlError(g_real, n, o); };
    vfs_.xDlSym = [](sqlite3_vfs*, void* h, const char* s) { return g_real->xDlSym(g_real, h, s); };
    vfs_.xDlClose = [](sqlite3_vfs*, void* h) { g_real->xDlClose(g_real, h); };
    vfs_.xRandomness = [](sqlite3_vfs*, int n, char* o) { return g_real->xRandomness(g_real, n, o); };
    vfs_.xSleep = [](sqlite3_vfs*, int us) { return g_real->xSleep(g_real, us); };
    vfs_.xCurrentTime = [](sqlite3_vfs*, double* t) { return g_real->xCurrentTime(g_real, t); };
    vfs_.xGetLastError = [](sqlite3_vfs*, int n, char* o) { return g_real->xGetLastError(g_real, n, o); };
    sqlite3_vfs_register(&vfs_, 1);  // the default: read_session opens through it
  }
  ~ShimVfs() {
    sqlite3_vfs_unregister(&vfs_);
    g_hook = nullptr;
  }
  ShimVfs(const ShimVfs&) = delete;
  ShimVfs& operator=(const ShimVfs&) = delete;

 private:
  sqlite3_vfs vfs_{};
};

TEST(SessionSnapshot, ACommitDuringAReadDoesNotShowHalfway) {
  test::ScratchDir dir;
  const auto path = dir / "live.palpa";
  SessionWriter writer(path, test::flat_case_info());  // opened through the real VFS
  Event e;
  e.kind = EventKind::Start;
  writer.event(e);
  for (std::uint64_t k = 0; k < 100; ++k) writer.append(test::sample_at(k));
  writer.commit();

  bool committed = false;
  Session first;
  {
    ShimVfs shim;
    g_hook = [&] {  // the recorder's next commit: a pause and 100 more ticks
      Event pause;
      pause.t = 0.15;
      pause.kind = EventKind::Pause;
      writer.event(pause);
      for (std::uint64_t k = 100; k < 200; ++k) writer.append(test::sample_at(k));
      writer.commit();
      committed = true;
    };
    first = read_session(path);
  }
  ASSERT_TRUE(committed) << "the reader never ended a read transaction";
  // As of one commit: the first (1 event, 100 ticks); before one transaction per read it
  // was the first commit's meta and the second commit's events and ticks.
  EXPECT_EQ(first.events.size(), 1u);
  EXPECT_EQ(first.samples.size(), 100u);
  const auto second = read_session(path);
  EXPECT_EQ(second.events.size(), 2u);
  EXPECT_EQ(second.samples.size(), 200u);
}

}  // namespace
}  // namespace palpa::session
