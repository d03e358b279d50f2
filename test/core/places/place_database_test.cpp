// The SQLite place database: round trip, refusal of other settings, foreign and corrupt files,
// and a writer killed in the middle of its transactions.
#include "adaptive_perception/places/place_database.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <thread>

#include "../scratch_dir.h"

using namespace adaptive_perception::places;
namespace fs = std::filesystem;

namespace {

class PlaceDatabaseTest : public ::testing::Test {
 protected:
  void SetUp() override {
    settings_.bins = 8;
    settings_.spaces = {0, 4};
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  // Deterministic histograms: band mass at bin (seed + band) % bins.
  ImageHistograms hist(int seed) const {
    ImageHistograms h;
    h.bins = settings_.bins;
    for (int s : settings_.spaces) {
      h.spaces[s].assign(3 * h.bins, 0.0f);
      for (int band = 0; band < 3; ++band) {
        h.spaces[s][band * h.bins + (seed + band) % h.bins] = 0.75f;
        h.spaces[s][band * h.bins + (seed + band + s) % h.bins] += 0.25f;
      }
    }
    return h;
  }
  std::vector<TrainingImage> images(int first, int n) const {
    std::vector<TrainingImage> out;
    for (int i = first; i < first + n; ++i)
      out.push_back({"image_" + std::to_string(i) + ".png", 0.5 * i, hist(i), {}, {}, {}, {}});
    return out;
  }
  static std::string contents(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

  adaptive_perception::test_support::ScratchDir scratch_{"ap_places"};
  const fs::path& dir_ = scratch_.path();
  DatabaseSettings settings_;
};

}  // namespace

TEST_F(PlaceDatabaseTest, RoundTripMatchesAnInMemoryIndex) {
  PlaceIndex direct(settings_.bins);
  {
    PlaceDatabase db = PlaceDatabase::create(file("p.sqlite"), settings_);
    EXPECT_EQ(db.addImages("kitchen", images(0, 3)), 3);
    EXPECT_EQ(db.addImages("corridor", images(10, 2)), 2);
    EXPECT_EQ(db.addImages("kitchen", images(3, 1)), 1);
    db.setAdjacent("kitchen", "corridor");
    db.setAdjacent("corridor", "kitchen");  // the same edge
  }
  // Places come back in name order.
  const int c = direct.addPlace("corridor"), k = direct.addPlace("kitchen");
  for (const auto& ti : images(10, 2)) direct.addImage(c, ti.histograms);
  for (const auto& ti : images(0, 4)) direct.addImage(k, ti.histograms);

  PlaceDatabase db = PlaceDatabase::open(file("p.sqlite"), true);
  EXPECT_EQ(db.settings(), settings_);
  EXPECT_EQ(db.imageCount(), 6);
  const auto places = db.places();
  ASSERT_EQ(places.size(), 2u);
  EXPECT_EQ(places[0].name, "corridor");
  EXPECT_EQ(places[0].images, 2);
  EXPECT_EQ(places[1].images, 4);
  ASSERT_EQ(db.edges().size(), 1u);
  EXPECT_EQ(db.edges()[0], std::make_pair(std::string("corridor"), std::string("kitchen")));

  const PlaceIndex loaded = db.loadIndex();
  ASSERT_EQ(loaded.placeNames(), direct.placeNames());
  for (int s : settings_.spaces)
    for (Distance d : parseDistances("all")) {
      const auto a = loaded.nodeDistances(s, d, hist(2));
      const auto b = direct.nodeDistances(s, d, hist(2));
      for (size_t x = 0; x < a.size(); ++x) EXPECT_DOUBLE_EQ(a[x], b[x]);
    }
  EXPECT_EQ(db.adjacencyLists(loaded), (std::vector<std::vector<int>>{{1}, {0}}));
  // A space the database was not built with.
  EXPECT_THROW(db.loadIndex({2}), std::invalid_argument);
}

TEST_F(PlaceDatabaseTest, RemovePlaceAndEdges) {
  PlaceDatabase db = PlaceDatabase::create(file("p.sqlite"), settings_);
  db.addImages("a", images(0, 2));
  db.addImages("b", images(2, 2));
  db.addImages("c", images(4, 2));
  db.setAdjacent("a", "b");
  db.setAdjacent("b", "c");
  EXPECT_THROW(db.setAdjacent("a", "nowhere"), std::invalid_argument);
  EXPECT_TRUE(db.removePlace("b"));
  EXPECT_FALSE(db.removePlace("b"));
  EXPECT_EQ(db.imageCount(), 4);
  EXPECT_TRUE(db.edges().empty());
  db.setAdjacent("a", "c");
  db.setAdjacent("a", "c", false);
  EXPECT_TRUE(db.edges().empty());
  EXPECT_EQ(db.loadIndex().totalImages(0), 4);
}

TEST_F(PlaceDatabaseTest, RefusesOtherSettingsAndBadImages) {
  PlaceDatabase db = PlaceDatabase::create(file("p.sqlite"), settings_);
  DatabaseSettings other = settings_;
  other.bins = 16;
  try {
    db.requireSettings(other);
    FAIL() << "other bins accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bins=8"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bins=16"), std::string::npos) << e.what();
  }
  other = settings_;
  other.mask = MaskConfig::parse("ring:10,10,2,8");
  EXPECT_THROW(db.requireSettings(other), std::runtime_error);
  EXPECT_NO_THROW(db.requireSettings(settings_));
  // An image without one of the spaces: nothing is stored.
  std::vector<TrainingImage> bad = images(0, 2);
  bad[1].histograms.spaces[4].clear();
  EXPECT_THROW(db.addImages("a", bad), std::invalid_argument);
  EXPECT_EQ(db.imageCount(), 0);
  EXPECT_TRUE(db.places().empty());
}

TEST_F(PlaceDatabaseTest, NeverReplacesAnExistingFile) {
  const std::string path = file("notes.sqlite");
  { std::ofstream(path) << "my notes\n"; }
  EXPECT_THROW(PlaceDatabase::create(path, settings_), std::runtime_error);
  EXPECT_EQ(contents(path), "my notes\n");
  PlaceDatabase::create(file("p.sqlite"), settings_);
  EXPECT_THROW(PlaceDatabase::create(file("p.sqlite"), settings_), std::runtime_error);
}

TEST_F(PlaceDatabaseTest, ForeignAndCorruptFilesGiveClearErrors) {
  // A text file.
  const std::string text = file("text.sqlite");
  { std::ofstream(text) << std::string(4096, 'x'); }
  try {
    PlaceDatabase::open(text);
    FAIL() << "a text file was opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not a place database"), std::string::npos) << e.what();
  }
  EXPECT_EQ(contents(text), std::string(4096, 'x'));
  // Another program's SQLite database.
  const std::string foreign = file("foreign.sqlite");
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(foreign.c_str(), &db), SQLITE_OK);
    sqlite3_exec(db, "CREATE TABLE t (x); INSERT INTO t VALUES (1);", nullptr, nullptr, nullptr);
    sqlite3_close(db);
  }
  const std::string before = contents(foreign);
  try {
    PlaceDatabase::open(foreign);
    FAIL() << "a foreign database was opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not an adaptive_perception place database"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(contents(foreign), before);
  // A place database whose pages were overwritten in the middle.
  const std::string broken = file("broken.sqlite");
  {
    PlaceDatabase db = PlaceDatabase::create(broken, settings_);
    db.addImages("a", images(0, 50));
  }
  {
    std::fstream f(broken, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(4096);
    const std::string junk(8192, '\x5a');
    f.write(junk.data(), junk.size());
  }
  EXPECT_THROW(
      {
        PlaceDatabase db = PlaceDatabase::open(broken);
        db.loadIndex();
      },
      std::runtime_error);
  EXPECT_THROW(PlaceDatabase::open(file("missing.sqlite")), std::runtime_error);
}

TEST_F(PlaceDatabaseTest, KilledWriterLeavesWholeTransactions) {
  const std::string path = file("p.sqlite");
  PlaceDatabase::create(path, settings_);
  const int batch = 20;
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    try {
      PlaceDatabase db = PlaceDatabase::open(path);
      for (int i = 0;; ++i) db.addImages("place_" + std::to_string(i % 3), images(i, batch));
    } catch (...) {
    }
    ::_exit(1);
  }
  // Let it commit some batches, then kill it wherever it is.
  for (int i = 0; i < 200; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    try {
      if (PlaceDatabase::open(path, true).imageCount() >= 3 * batch) break;
    } catch (const std::runtime_error&) {
    }
  }
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));

  PlaceDatabase db = PlaceDatabase::open(path);  // replays the hot journal, if any
  {
    sqlite3* raw = nullptr;
    ASSERT_EQ(sqlite3_open_v2(path.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    sqlite3_stmt* st = nullptr;
    sqlite3_prepare_v2(raw, "PRAGMA integrity_check", -1, &st, nullptr);
    ASSERT_EQ(sqlite3_step(st), SQLITE_ROW);
    EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(st, 0)), "ok");
    sqlite3_finalize(st);
    sqlite3_close(raw);
  }
  const long n = db.imageCount();
  EXPECT_GE(n, 3 * batch);
  EXPECT_EQ(n % batch, 0) << "a half-written batch survived";
  const PlaceIndex index = db.loadIndex();
  for (int s : settings_.spaces) EXPECT_EQ(index.totalImages(s), n);
  // And it still takes writes.
  db.addImages("after", images(0, 1));
  EXPECT_EQ(db.imageCount(), n + 1);
}

// A writer that dies inside a batch leaves a hot journal; a READ-ONLY open rolls it back, says so,
// and sees the database as it was before the batch (none of the batch's places or edges).
TEST_F(PlaceDatabaseTest, AReaderRecoversTheHotJournalOfAWriterKilledInABatch) {
  const std::string path = file("p.sqlite");
  {
    PlaceDatabase db = PlaceDatabase::create(path, settings_);
    db.addImages("kept", images(0, 4));
  }
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    try {
      PlaceDatabase db = PlaceDatabase::open(path);
      db.beginBatch();
      // Enough to spill SQLite's 2 MB page cache: the file itself then holds uncommitted pages
      // and the journal their originals (a journal with nothing to undo would not be hot).
      for (int i = 0; i < 200; ++i) db.addImages("lost_" + std::to_string(i), images(i, 100));
      db.setAdjacent("lost_0", "lost_1");
      ::_exit(0);  // dies without committing, as a kill would
    } catch (...) {
    }
    ::_exit(1);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  ASSERT_TRUE(fs::exists(path + "-journal")) << "no hot journal: the case did not happen";

  const PlaceDatabase reader = PlaceDatabase::open(path, true);
  EXPECT_TRUE(reader.recoveredJournal());
  EXPECT_EQ(reader.imageCount(), 4);
  ASSERT_EQ(reader.places().size(), 1u);
  EXPECT_EQ(reader.places()[0].name, "kept");
  EXPECT_TRUE(reader.edges().empty());
  EXPECT_FALSE(PlaceDatabase::open(path, true).recoveredJournal());  // nothing left to recover
}

// Another program's SQLite file with the hot journal of a write it did not finish: open() tells
// from the bytes (the file's header and the journal's copy of page 1) that it is no place
// database, and refuses it before SQLite rolls the journal back: read-only or not, the file and
// its journal stay as they were, byte for byte.
TEST_F(PlaceDatabaseTest, AForeignDatabaseWithAHotJournalIsRefusedAndNotRolledBack) {
  const std::string rows =
      "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n WHERE i < 2000) "
      "INSERT INTO t SELECT randomblob(500) FROM n;";
  // A child that writes with a page cache of 4 pages (the changed pages spill into the file,
  // their originals into the journal) and dies before committing.
  const auto dieWriting = [](const std::string& path, const std::string& sql) {
    const pid_t child = ::fork();
    if (child == 0) {
      sqlite3* db = nullptr;
      const bool ok = sqlite3_open(path.c_str(), &db) == SQLITE_OK &&
                      sqlite3_exec(db, ("PRAGMA cache_size = 4; BEGIN; " + sql).c_str(), nullptr,
                                   nullptr, nullptr) == SQLITE_OK;
      ::_exit(ok ? 0 : 1);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    return child > 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  };
  // Both ways of opening refuse it, naming it and saying `what`, and change nothing.
  const auto refusedUntouched = [&](const std::string& path, const std::string& what) {
    const std::string journal = path + "-journal";
    ASSERT_TRUE(fs::exists(journal)) << "no hot journal: the case did not happen";
    const std::string file_before = contents(path), journal_before = contents(journal);
    for (const bool read_only : {true, false}) {
      SCOPED_TRACE(read_only ? "read-only" : "read-write");
      try {
        PlaceDatabase::open(path, read_only);
        ADD_FAILURE() << "a foreign database was opened";
      } catch (const std::runtime_error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
        EXPECT_NE(msg.find(what), std::string::npos) << msg;
        EXPECT_NE(msg.find("untouched"), std::string::npos) << msg;
      }
      EXPECT_TRUE(contents(path) == file_before) << "the foreign file was written";
      ASSERT_TRUE(fs::exists(journal)) << "the foreign journal was rolled back";
      EXPECT_TRUE(contents(journal) == journal_before) << "the foreign journal was changed";
    }
  };
  // The header of a place database: SQLite's, with our application_id at byte 68.
  const std::string ours =
      contents(PlaceDatabase::create(file("ours.sqlite"), settings_).path()).substr(0, 100);
  const auto writeHeader = [](const std::string& path, const std::string& header) {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.write(header.data(), static_cast<std::streamsize>(header.size()));
  };

  struct Case {
    std::string name;
    unsigned app_id;    // the file's before the write
    bool ours_on_disk;  // its header in the file says ours: only the journal's page 1 tells
  };
  for (const Case& c : {Case{"plain.sqlite", 0, false}, Case{"other.sqlite", 0x46524a47, false},
                        Case{"disguised.sqlite", 0x46524a47, true}}) {
    SCOPED_TRACE(c.name);
    const std::string path = file(c.name);
    {
      sqlite3* db = nullptr;
      ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
      const std::string sql =
          "PRAGMA application_id = " + std::to_string(c.app_id) + "; CREATE TABLE t (x); " + rows;
      ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
      sqlite3_close(db);
    }
    ASSERT_TRUE(dieWriting(path, "UPDATE t SET x = randomblob(600); " + rows));
    if (c.ours_on_disk) {
      std::string header = contents(path).substr(0, 100);
      header.replace(68, 4, ours, 68, 4);
      writeHeader(path, header);
    }
    refusedUntouched(path, "not an adaptive_perception place database");
  }
  // A new file whose first write was interrupted: its rollback would leave it empty. Its page 1
  // never reached the file; and when it has (written here) with our application_id, the journal
  // still tells that the file was empty before.
  const std::string fresh = file("fresh.sqlite");
  ASSERT_TRUE(dieWriting(fresh, "CREATE TABLE t (x); " + rows));
  refusedUntouched(fresh, "not a place database");
  writeHeader(fresh, ours);
  refusedUntouched(fresh, "not a place database");
}

TEST_F(PlaceDatabaseTest, ABatchCommitsAsAWholeAndASecondWriterIsRefusedAtOnce) {
  const std::string path = file("p.sqlite");
  PlaceDatabase first = PlaceDatabase::create(path, settings_);
  first.beginBatch();
  first.addImages("a", images(0, 3));
  first.addImages("b", images(3, 3));
  first.setAdjacent("a", "b");
  PlaceDatabase second = PlaceDatabase::open(path);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    second.beginBatch();
    FAIL() << "a second writer was let in";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("another process is writing"), std::string::npos)
        << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0)
      << "the refusal waited";
  EXPECT_EQ(PlaceDatabase::open(path, true).imageCount(), 0) << "readers see the batch early";
  first.commitBatch();
  EXPECT_EQ(PlaceDatabase::open(path, true).imageCount(), 6);
  EXPECT_EQ(PlaceDatabase::open(path, true).edges().size(), 1u);
  second.beginBatch();  // free now
  second.addImages("c", images(6, 1));
  second.commitBatch();
  EXPECT_EQ(PlaceDatabase::open(path, true).imageCount(), 7);
}

TEST_F(PlaceDatabaseTest, ABatchNotCommittedLeavesNothing) {
  const std::string path = file("p.sqlite");
  {
    PlaceDatabase db = PlaceDatabase::create(path, settings_);
    db.beginBatch();
    db.addImages("a", images(0, 3));
  }  // destroyed without commitBatch (an exception in a training run)
  EXPECT_EQ(PlaceDatabase::open(path, true).imageCount(), 0);
}

TEST_F(PlaceDatabaseTest, ReplaceImagesReplacesAPlacesImagesAndKeepsItsEdges) {
  const std::string path = file("p.sqlite");
  PlaceDatabase db = PlaceDatabase::create(path, settings_);
  db.addImages("a", images(0, 5));
  db.addImages("b", images(5, 2));
  db.setAdjacent("a", "b");
  int replaced = -1;
  EXPECT_EQ(db.replaceImages("a", images(10, 3), &replaced), 3);
  EXPECT_EQ(replaced, 5);
  EXPECT_EQ(db.imageCount(), 5);  // 3 of a + 2 of b, not 10
  EXPECT_EQ(db.edges().size(), 1u);
  const PlaceIndex index = db.loadIndex();
  for (int s : settings_.spaces) EXPECT_EQ(index.totalImages(s), 5);
  EXPECT_EQ(db.replaceImages("new", images(0, 1), &replaced), 1);
  EXPECT_EQ(replaced, 0);
}

TEST_F(PlaceDatabaseTest, SiftFeaturesAndPosesRoundTrip) {
  std::vector<TrainingImage> imgs = images(0, 3);
  cv::Mat f(5, 128, CV_32F);
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 128; ++c) f.at<float>(r, c) = static_cast<float>((r * 131 + c * 7) % 256);
  imgs[0].features = f;
  imgs[0].pose = std::array<double, 3>{1.5, -2.0, 0.25};
  imgs[2].features = f.rowRange(0, 2).clone();  // no pose
  const cv::Mat structure = (cv::Mat_<float>(1, 4) << 0.5f, 0.0f, 0.125f, 1e-3f);
  imgs[0].structure = structure;  // only the first has a line-structure descriptor
  {
    PlaceDatabase db = PlaceDatabase::create(file("p.sqlite"), settings_);
    db.addImages("lab", imgs);
    cv::Mat bad(2, 64, CV_32F, cv::Scalar(1));
    std::vector<TrainingImage> wrong = images(5, 1);
    wrong[0].features = bad;
    EXPECT_THROW(db.addImages("lab", wrong), std::invalid_argument);
    wrong = images(6, 1);
    wrong[0].structure = cv::Mat(2, 2, CV_32F, cv::Scalar(1));  // not one row
    EXPECT_THROW(db.addImages("lab", wrong), std::invalid_argument);
  }
  const PlaceDatabase db = PlaceDatabase::open(file("p.sqlite"), true);
  const auto frames = db.loadFrames();
  ASSERT_EQ(frames.size(), 2u);  // the image without features is no frame
  EXPECT_EQ(frames[0].place, "lab");
  EXPECT_EQ(cv::norm(frames[0].features, f, cv::NORM_INF), 0.0);
  EXPECT_TRUE(frames[0].has_pose);
  EXPECT_DOUBLE_EQ(frames[0].x_m, 1.5);
  EXPECT_DOUBLE_EQ(frames[0].yaw_rad, 0.25);
  EXPECT_EQ(cv::norm(frames[0].structure, structure, cv::NORM_INF), 0.0);
  EXPECT_EQ(frames[1].features.rows, 2);
  EXPECT_FALSE(frames[1].has_pose);
  EXPECT_TRUE(frames[1].structure.empty());
  EXPECT_EQ(db.imageCount(), 3);
}

// A stored value no reader can use (written by another program, or a damaged file): refused
// when read, naming the file, the image and the value, and the file left as it was.
TEST_F(PlaceDatabaseTest, StoredValuesThatCannotBeUsedAreRefusedWhenRead) {
  const auto setBlob = [](const std::string& path, const std::string& sql,
                          const std::vector<float>& values) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    sqlite3_stmt* st = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr), SQLITE_OK) << sql;
    sqlite3_bind_blob(st, 1, values.data(), static_cast<int>(values.size() * sizeof(float)),
                      SQLITE_TRANSIENT);
    EXPECT_EQ(sqlite3_step(st), SQLITE_DONE);
    sqlite3_finalize(st);
    sqlite3_close(db);
  };
  const auto refusal = [](const std::function<void()>& read) -> std::string {
    try {
      read();
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  };
  const int values = 3 * settings_.bins;
  const std::string first_histogram =
      "UPDATE histograms SET data = ?1 WHERE rowid = (SELECT MIN(rowid) FROM histograms)";
  const float nan = std::numeric_limits<float>::quiet_NaN();
  struct Case {
    std::string name, sql;
    std::vector<float> blob;
    std::string expected;
  };
  std::vector<float> with_nan(values, 0.1f), negative(values, 0.1f), infinite(4, 0.5f);
  with_nan[5] = nan;
  negative[2] = -0.5f;
  infinite[3] = std::numeric_limits<float>::infinity();
  const std::vector<Case> cases = {
      {"nan_bin", first_histogram, with_nan, "histogram (value 5 is nan)"},
      {"negative_bin", first_histogram, negative, "histogram (value 2 is -0.5"},
      {"infinite_structure", "UPDATE structure SET data = ?1", infinite,
       "line-structure blob (value 3 is infinite)"},
      {"infinite_pose", "UPDATE poses SET x_m = 9e999 WHERE ?1 IS NOT NULL", {0.0f},
       "has a pose that is not finite"}};
  for (const Case& c : cases) {
    const std::string path = file(c.name + ".sqlite");
    {
      std::vector<TrainingImage> imgs = images(0, 2);
      imgs[0].features = cv::Mat(2, 128, CV_32F, cv::Scalar(3));
      imgs[0].pose = std::array<double, 3>{1.0, 2.0, 0.5};
      imgs[0].structure = (cv::Mat_<float>(1, 4) << 0.5f, 0.0f, 0.125f, 1e-3f);
      PlaceDatabase db = PlaceDatabase::create(path, settings_);
      db.addImages("lab", imgs);
    }
    setBlob(path, c.sql, c.blob);
    const std::string before = contents(path);
    const PlaceDatabase db = PlaceDatabase::open(path, true);
    const std::string e = refusal([&] {
      db.loadIndex();
      db.loadFrames();
    });
    EXPECT_NE(e.find(path + ": image 1 has"), std::string::npos) << c.name << ": " << e;
    EXPECT_NE(e.find(c.expected), std::string::npos) << c.name << ": " << e;
    EXPECT_EQ(contents(path), before) << c.name;
  }
}

TEST_F(PlaceDatabaseTest, WholeImageDescriptorsRoundTripAndRefuseOtherSettings) {
  const GlobalDescriptorConfig dc;
  const auto withDescriptors = [&](int first, int n) {
    std::vector<TrainingImage> v = images(first, n);
    for (size_t i = 0; i < v.size(); ++i) {
      cv::Mat img(64, 96, CV_8UC3);
      cv::randu(img, 0, 256);
      v[i].descriptors = computeDescriptors(img, dc);
    }
    return v;
  };
  const std::vector<TrainingImage> kitchen = withDescriptors(0, 2), hall = withDescriptors(5, 1);
  {
    PlaceDatabase db = PlaceDatabase::create(file("d.sqlite"), settings_);
    EXPECT_EQ(db.descriptorSettings(), "");
    EXPECT_THROW(db.addImages("kitchen", kitchen), std::logic_error);  // settings not declared
    db.useDescriptors(dc);
    db.addImages("kitchen", kitchen);
    db.addImages("hall", hall);
    db.addImages("hall", images(7, 1));  // an image without descriptors is allowed
  }
  const PlaceDatabase db = PlaceDatabase::open(file("d.sqlite"), true);
  EXPECT_EQ(db.descriptorSettings(), dc.toString());
  const PlaceIndex index = db.loadIndex();
  const PlaceDescriptorIndex d = db.loadDescriptorIndex(index, dc);
  ASSERT_EQ(d.totalImages(), 3);
  ASSERT_EQ(d.placeNames(), index.placeNames());  // hall, kitchen
  // The stored kitchen image 1 is its own nearest image: distance 0 at kitchen.
  const std::vector<double> nd = d.nodeDistances({1.0, 1.0, 1.0}, kitchen[1].descriptors);
  EXPECT_EQ(nd[index.placeIndex("kitchen")], 0.0);
  EXPECT_GT(nd[index.placeIndex("hall")], 0.0);
  // Other settings: refused, both named.
  GlobalDescriptorConfig other;
  other.thumbnail_width_px = 32;
  try {
    db.loadDescriptorIndex(index, other);
    ADD_FAILURE() << "other descriptor settings were accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dc.toString()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(other.toString()), std::string::npos) << e.what();
  }
  PlaceDatabase rw = PlaceDatabase::open(file("d.sqlite"));
  EXPECT_THROW(rw.useDescriptors(other), std::runtime_error);
  // Replacing a place's images removes its descriptors with them.
  rw.replaceImages("kitchen", images(20, 1));
  EXPECT_EQ(rw.loadDescriptorIndex(rw.loadIndex(), dc).totalImages(), 1);
  rw.removePlace("hall");
  EXPECT_EQ(rw.loadDescriptorIndex(rw.loadIndex(), dc).totalImages(), 0);
}
