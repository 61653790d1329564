// The disk cache of the structure's modes (docs/architecture.md "Mode cache"): a read gives the
// computed modes bit for bit; another matrix or option misses; a damaged file is recomputed and
// replaced; an unwritable folder costs only the cache; the folder's choice from the environment;
// at most kMaxModalCacheFiles files kept.
#include "crane_twin/structure/modal_cache.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"

using namespace crane_twin;
namespace fs = std::filesystem;

namespace {

// A fixed-fixed chain of n masses and springs with a soft ground spring at every mass (K
// positive definite), its masses and stiffnesses graded so the frequencies are distinct; its
// lowest `count` modes asked for.
struct ModeProblem {
  SparseMatrix K, M;
  ModalOptions opt;
};

ModeProblem springChain(int n, double k_scale, int count) {
  SparseAssembler KA(n), MA(n);
  for (int i = 0; i < n; ++i) {
    const double k = k_scale * (1.0 + 0.01 * i);
    Eigen::Matrix2d ke;
    ke << k, -k, -k, k;
    if (i + 1 < n) KA.add(ke, {i, i + 1});
    Eigen::Matrix<double, 1, 1> kg, m;
    kg << 0.1 * k + (i == 0 ? k : 0.0);
    m << 1.0 + 0.002 * i;
    KA.add(kg, {i});
    MA.add(m, {i});
  }
  ModeProblem p;
  p.K = KA.build();
  p.M = MA.build();
  p.opt.count = count;
  return p;
}

// An environment variable set or unset for a scope, restored at its end (an ASSERT's early
// return included).
class ScopedEnv {
 public:
  explicit ScopedEnv(const char* name) : name_(name) {
    if (const char* v = std::getenv(name)) saved_ = v;
  }
  ~ScopedEnv() {
    if (saved_)
      ::setenv(name_, saved_->c_str(), 1);
    else
      ::unsetenv(name_);
  }
  void set(const std::string& value) { ::setenv(name_, value.c_str(), 1); }
  void unset() { ::unsetenv(name_); }

 private:
  const char* name_;
  std::optional<std::string> saved_;
};

// A fresh folder under the system's temporary one, removed with the fixture.
class ModalCache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("crane_twin_mode_cache_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  int files() const {
    int n = 0;
    if (!fs::exists(dir_)) return 0;
    for (const auto& e : fs::directory_iterator(dir_)) n += e.is_regular_file() ? 1 : 0;
    return n;
  }
  fs::path dir_;
};

void expectBitwiseEqual(const ModalBasis& a, const ModalBasis& b) {
  ASSERT_EQ(a.omega2.size(), b.omega2.size());
  ASSERT_EQ(a.phi.rows(), b.phi.rows());
  ASSERT_EQ(a.phi.cols(), b.phi.cols());
  EXPECT_TRUE((a.omega2.array() == b.omega2.array()).all());
  EXPECT_TRUE((a.phi.array() == b.phi.array()).all());
}

}  // namespace

TEST_F(ModalCache, ASecondRunReadsTheComputedModesBitForBit) {
  const ModeProblem p = springChain(200, 1e4, 12);
  const ModalBasis direct = lowestModes(p.K, p.M, p.opt);
  ModalCacheOutcome o;
  const ModalBasis first = cachedLowestModes(p.K, p.M, p.opt, dir_.string(), &o);
  EXPECT_EQ(o, ModalCacheOutcome::computed_and_written);
  EXPECT_EQ(files(), 1);
  const ModalBasis second = cachedLowestModes(p.K, p.M, p.opt, dir_.string(), &o);
  EXPECT_EQ(o, ModalCacheOutcome::read);
  expectBitwiseEqual(first, direct);
  expectBitwiseEqual(second, direct);
}

TEST_F(ModalCache, AnotherMatrixOrModeCountMisses) {
  const ModeProblem p = springChain(150, 1e4, 8);
  const ModeProblem q = springChain(150, 1e4 * (1.0 + 1e-15), 8);  // values differ in the last bits
  ModalCacheOutcome o;
  cachedLowestModes(p.K, p.M, p.opt, dir_.string(), &o);
  ASSERT_EQ(o, ModalCacheOutcome::computed_and_written);
  const ModalBasis other = cachedLowestModes(q.K, q.M, q.opt, dir_.string(), &o);
  EXPECT_EQ(o, ModalCacheOutcome::computed_and_written);
  expectBitwiseEqual(other, lowestModes(q.K, q.M, q.opt));
  ModalOptions opt = p.opt;
  opt.count = 9;
  cachedLowestModes(p.K, p.M, opt, dir_.string(), &o);
  EXPECT_EQ(o, ModalCacheOutcome::computed_and_written);
  opt.count = 8;
  opt.tolerance = 1e-10;
  cachedLowestModes(p.K, p.M, opt, dir_.string(), &o);
  EXPECT_EQ(o, ModalCacheOutcome::computed_and_written);
  EXPECT_EQ(files(), 4);
}

TEST_F(ModalCache, ADamagedFileIsRecomputedAndReplaced) {
  const ModeProblem p = springChain(120, 1e4, 6);
  const ModalBasis direct = lowestModes(p.K, p.M, p.opt);
  ModalCacheOutcome o;
  cachedLowestModes(p.K, p.M, p.opt, dir_.string(), &o);
  ASSERT_EQ(files(), 1);
  const fs::path file = fs::directory_iterator(dir_)->path();
  const auto size = fs::file_size(file);
  {  // one byte of a mode shape flipped
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(size / 2));
    f.put(static_cast<char>(0x5a));
  }
  expectBitwiseEqual(cachedLowestModes(p.K, p.M, p.opt, dir_.string(), &o), direct);
  EXPECT_EQ(o, ModalCacheOutcome::computed_and_written);
  expectBitwiseEqual(cachedLowestModes(p.K, p.M, p.opt, dir_.string(), &o), direct);
  EXPECT_EQ(o, ModalCacheOutcome::read) << "the recomputed file replaced the damaged one";
  fs::resize_file(file, size - 9);  // truncated
  expectBitwiseEqual(cachedLowestModes(p.K, p.M, p.opt, dir_.string(), &o), direct);
  EXPECT_EQ(o, ModalCacheOutcome::computed_and_written);
  EXPECT_EQ(files(), 1) << "no temporary file left behind";
}

TEST_F(ModalCache, AFolderThatCannotBeWrittenCostsOnlyTheCache) {
  const ModeProblem p = springChain(100, 1e4, 5);
  fs::create_directories(dir_);
  std::ofstream(dir_ / "a_file") << "not a folder";
  ModalCacheOutcome o;
  const ModalBasis b = cachedLowestModes(p.K, p.M, p.opt, (dir_ / "a_file" / "cache").string(), &o);
  EXPECT_EQ(o, ModalCacheOutcome::computed_not_written);
  expectBitwiseEqual(b, lowestModes(p.K, p.M, p.opt));
  cachedLowestModes(p.K, p.M, p.opt, std::nullopt, &o);
  EXPECT_EQ(o, ModalCacheOutcome::no_cache);
}

TEST_F(ModalCache, KeepsAtMostItsLimitOfFiles) {
  const auto chain = [](int i) { return springChain(40, 1e4 * (1.0 + 0.1 * i), 3); };
  for (int i = 0; i < kMaxModalCacheFiles + 4; ++i) {
    const ModeProblem p = chain(i);
    cachedLowestModes(p.K, p.M, p.opt, dir_.string());
  }
  EXPECT_EQ(files(), kMaxModalCacheFiles);
  // The newest survived: the last matrix is read, not recomputed.
  const ModeProblem last = chain(kMaxModalCacheFiles + 3);
  ModalCacheOutcome o;
  cachedLowestModes(last.K, last.M, last.opt, dir_.string(), &o);
  EXPECT_EQ(o, ModalCacheOutcome::read);
}

TEST_F(ModalCache, ATemporaryFileAnHourOldIsRemovedAFreshOneKept) {
  fs::create_directories(dir_);
  const fs::path old_tmp = dir_ / ".modes-0123.bin.42.0.tmp",
                 new_tmp = dir_ / ".modes-4567.bin.43.0.tmp";
  std::ofstream(old_tmp) << "half a file";
  std::ofstream(new_tmp) << "being written";
  fs::last_write_time(old_tmp, fs::file_time_type::clock::now() - std::chrono::hours(2));
  const ModeProblem p = springChain(40, 1e4, 3);
  cachedLowestModes(p.K, p.M, p.opt, dir_.string());
  EXPECT_FALSE(fs::exists(old_tmp));
  EXPECT_TRUE(fs::exists(new_tmp));
}

TEST_F(ModalCache, TheFolderFollowsTheEnvironment) {
  ScopedEnv cache("CRANE_TWIN_CACHE_DIR"), xdg("XDG_CACHE_HOME"), home("HOME");
  cache.set("/somewhere/modes");
  EXPECT_EQ(modalCacheDirectory(), std::optional<std::string>("/somewhere/modes"));
  cache.set("");
  EXPECT_EQ(modalCacheDirectory(), std::nullopt) << "set and empty: no cache";
  cache.unset();
  xdg.set("/xdg");
  home.set("/home/crane");
  EXPECT_EQ(modalCacheDirectory(), std::optional<std::string>("/xdg/crane_twin"));
  xdg.unset();
  EXPECT_EQ(modalCacheDirectory(), std::optional<std::string>("/home/crane/.cache/crane_twin"));
  home.unset();
  EXPECT_EQ(modalCacheDirectory(), std::nullopt);
}

// The T8036's 100 modes as the model builds them: the same bits read as computed.
TEST_F(ModalCache, TheT8036ModelReadsItsModesBitForBit) {
  const Scene sc =
      loadScene(std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_combination1.yaml");
  ScopedEnv cache("CRANE_TWIN_CACHE_DIR");
  cache.set("");
  const CraneModel computed = buildCraneModel(sc);
  cache.set(dir_.string());
  const CraneModel written = buildCraneModel(sc);
  ASSERT_EQ(files(), 1);
  const CraneModel read = buildCraneModel(sc);
  ASSERT_TRUE(computed.structure_modal_basis && read.structure_modal_basis);
  EXPECT_EQ(read.structure_modal_basis->phi.cols(), sc.structure_modes);
  expectBitwiseEqual(*written.structure_modal_basis, *computed.structure_modal_basis);
  expectBitwiseEqual(*read.structure_modal_basis, *computed.structure_modal_basis);
}
