#include "crane_twin/structure/modal_cache.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>
#include <vector>

namespace crane_twin {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'C', 'T', 'M', 'O', 'D', 'E', 'S', '1'};

// FNV-1a, 64 bits: h = (h xor byte) * 1099511628211 over the bytes, from an offset basis (the
// standard one unless given).
constexpr std::uint64_t kFnvOffsetBasis = 14695981039346656037ULL;
struct Fnv1a {
  std::uint64_t h = kFnvOffsetBasis;
  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  }
  template <class T>
  void addValue(const T& v) {
    add(&v, sizeof v);
  }
};

struct Key {
  std::uint64_t a = 0, b = 0;
  bool operator==(const Key& o) const { return a == o.a && b == o.b; }
};

// Both hashes over the same bytes: the standard offset basis and a second one.
struct KeyHash {
  Fnv1a a, b{0x84222325cbf29ce4ULL};
  void add(const void* data, std::size_t bytes) {
    a.add(data, bytes);
    b.add(data, bytes);
  }
  template <class T>
  void addValue(const T& v) {
    add(&v, sizeof v);
  }
  void addMatrix(const SparseMatrix& S) {
    SparseMatrix c;
    const SparseMatrix* m = &S;
    if (!S.isCompressed()) {
      c = S;
      c.makeCompressed();
      m = &c;
    }
    const std::int64_t rows = m->rows(), cols = m->cols(), nnz = m->nonZeros();
    addValue(rows);
    addValue(cols);
    addValue(nnz);
    add(m->outerIndexPtr(), sizeof(SparseMatrix::StorageIndex) * (cols + 1));
    add(m->innerIndexPtr(), sizeof(SparseMatrix::StorageIndex) * nnz);
    add(m->valuePtr(), sizeof(double) * nnz);
  }
};

Key keyOf(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& opt) {
  KeyHash h;
  h.add(kMagic, sizeof kMagic);
  h.addMatrix(K);
  h.addMatrix(M);
  const std::int64_t count = opt.count, iterations = opt.max_iterations;
  h.addValue(count);
  h.addValue(opt.shift);
  h.addValue(opt.tolerance);
  h.addValue(iterations);
  return {h.a.h, h.b.h};
}

std::string hex(std::uint64_t v) {
  static const char* digits = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 15; i >= 0; --i, v >>= 4) s[i] = digits[v & 0xf];
  return s;
}

std::string fileName(const Key& k) { return "modes-" + hex(k.a) + hex(k.b) + ".bin"; }

// The file: magic, key (2 x u64), n and nev (i64), omega2 (nev doubles), phi (n x nev doubles,
// column-major), then FNV-1a of all that.
std::vector<char> serialize(const Key& key, const ModalBasis& b) {
  const std::int64_t n = b.phi.rows(), nev = b.phi.cols();
  std::vector<char> out;
  const auto put = [&](const void* p, std::size_t bytes) {
    const char* c = static_cast<const char*>(p);
    out.insert(out.end(), c, c + bytes);
  };
  put(kMagic, sizeof kMagic);
  put(&key.a, sizeof key.a);
  put(&key.b, sizeof key.b);
  put(&n, sizeof n);
  put(&nev, sizeof nev);
  put(b.omega2.data(), sizeof(double) * nev);
  put(b.phi.data(), sizeof(double) * n * nev);
  Fnv1a h;
  h.add(out.data(), out.size());
  put(&h.h, sizeof h.h);
  return out;
}

std::optional<ModalBasis> deserialize(const std::vector<char>& in, const Key& key, std::int64_t n,
                                      std::int64_t nev) {
  const std::size_t head = sizeof kMagic + 2 * sizeof(std::uint64_t) + 2 * sizeof(std::int64_t);
  const std::size_t body = sizeof(double) * static_cast<std::size_t>(nev * (n + 1));
  if (in.size() != head + body + sizeof(std::uint64_t)) return std::nullopt;
  Fnv1a h;
  h.add(in.data(), head + body);
  std::uint64_t stored;
  std::memcpy(&stored, in.data() + head + body, sizeof stored);
  if (stored != h.h || std::memcmp(in.data(), kMagic, sizeof kMagic) != 0) return std::nullopt;
  Key k;
  std::int64_t fn, fnev;
  const char* p = in.data() + sizeof kMagic;
  const auto take = [&p](void* to, std::size_t bytes) {
    std::memcpy(to, p, bytes);
    p += bytes;
  };
  take(&k.a, sizeof k.a);
  take(&k.b, sizeof k.b);
  take(&fn, sizeof fn);
  take(&fnev, sizeof fnev);
  if (!(k == key) || fn != n || fnev != nev) return std::nullopt;
  ModalBasis b;
  b.omega2.resize(nev);
  b.phi.resize(n, nev);
  take(b.omega2.data(), sizeof(double) * nev);
  take(b.phi.data(), sizeof(double) * n * nev);
  if (!b.omega2.allFinite() || !b.phi.allFinite()) return std::nullopt;
  return b;
}

std::optional<std::vector<char>> readFile(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return std::nullopt;
  std::vector<char> data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (f.bad()) return std::nullopt;
  return data;
}

// Written under a name of its own, then renamed into place (atomic within one file system).
bool writeFile(const fs::path& dir, const std::string& name, const std::vector<char>& data) {
  static std::atomic<unsigned> counter{0};
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return false;
  const fs::path tmp = dir / ("." + name + "." + std::to_string(::getpid()) + "." +
                              std::to_string(counter++) + ".tmp");
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) return false;
    f.write(data.data(), static_cast<std::streamsize>(data.size()));
    f.close();
    if (!f) {
      fs::remove(tmp, ec);
      return false;
    }
  }
  fs::rename(tmp, dir / name, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return false;
  }
  return true;
}

// The oldest files (by modification time, which a read renews) beyond kMaxModalCacheFiles go,
// and temporary files an hour old (a run stopped while writing one).
void prune(const fs::path& dir) {
  std::error_code ec;
  std::vector<std::pair<fs::file_time_type, fs::path>> files;
  const auto stale = fs::file_time_type::clock::now() - std::chrono::hours(1);
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::error_code tec;
    const auto t = fs::last_write_time(it->path(), tec);
    if (tec) continue;
    if (name.rfind(".modes-", 0) == 0 && it->path().extension() == ".tmp") {
      if (t < stale) fs::remove(it->path(), tec);
      continue;
    }
    if (name.rfind("modes-", 0) != 0 || it->path().extension() != ".bin") continue;
    files.emplace_back(t, it->path());
  }
  if (static_cast<int>(files.size()) <= kMaxModalCacheFiles) return;
  std::sort(files.begin(), files.end());
  for (std::size_t i = 0; i + kMaxModalCacheFiles < files.size(); ++i)
    fs::remove(files[i].second, ec);
}

}  // namespace

std::optional<std::string> modalCacheDirectory() {
  if (const char* d = std::getenv("CRANE_TWIN_CACHE_DIR")) {
    if (*d == '\0') return std::nullopt;
    return std::string(d);
  }
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x == '/') {
    return (fs::path(x) / "crane_twin").string();
  }
  if (const char* home = std::getenv("HOME"); home && *home == '/') {
    return (fs::path(home) / ".cache" / "crane_twin").string();
  }
  return std::nullopt;
}

ModalBasis cachedLowestModes(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& opt,
                             const std::optional<std::string>& directory,
                             ModalCacheOutcome* outcome) {
  const auto report = [&](ModalCacheOutcome o) {
    if (outcome) *outcome = o;
  };
  if (!directory) {
    report(ModalCacheOutcome::no_cache);
    return lowestModes(K, M, opt);
  }
  const Key key = keyOf(K, M, opt);
  const fs::path dir(*directory);
  const std::string name = fileName(key);
  if (const auto data = readFile(dir / name)) {
    if (auto b = deserialize(*data, key, K.rows(), opt.count)) {
      std::error_code ec;
      fs::last_write_time(dir / name, fs::file_time_type::clock::now(), ec);
      report(ModalCacheOutcome::read);
      return std::move(*b);
    }
  }
  ModalBasis b = lowestModes(K, M, opt);
  if (writeFile(dir, name, serialize(key, b))) {
    prune(dir);
    report(ModalCacheOutcome::computed_and_written);
  } else {
    report(ModalCacheOutcome::computed_not_written);
  }
  return b;
}

ModalBasis cachedLowestModes(const SparseMatrix& K, const SparseMatrix& M,
                             const ModalOptions& opt) {
  return cachedLowestModes(K, M, opt, modalCacheDirectory());
}

}  // namespace crane_twin
