#include "storage/sqlite_model_store.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include <sqlite3.h>

#include "core/base/angles.h"
#include "storage/model_validation.h"
#include "storage/schema.h"
#include "storage/sqlite_connection.h"
#include "storage/sqlite_error.h"
#include "storage/sqlite_transaction.h"
#include "storage/store_copy.h"
#include "storage/store_files.h"

namespace orbit {
namespace {

constexpr int kMaxIdleReaders = 8;  // read connections kept open for reuse
constexpr int kEscalateCheckpointFactor = 4;
// How long an escalated checkpoint waits for readers in other processes.
constexpr std::chrono::milliseconds kCheckpointReaderWait(200);

constexpr const char* kNow = "strftime('%Y-%m-%dT%H:%M:%fZ', 'now')";

// The columns SummaryFromRow reads, in order.
#define ORBIT_SUMMARY_COLUMNS                                         \
  "o.id, o.name, o.variant, o.created_at, o.updated_at, o.metadata, " \
  "(SELECT count(*) FROM views v WHERE v.object_id = o.id)"

DescriptorVariant VariantFromColumn(std::string_view text, ObjectId id) {
  const std::optional<DescriptorVariant> variant = ParseVariant(text);
  if (!variant) {
    throw StoreError(StoreError::Code::kCorrupt, "object " + std::to_string(id) +
                                                     " has an unknown descriptor variant \"" +
                                                     std::string(text) + "\"");
  }
  return *variant;
}

ObjectSummary SummaryFromRow(const SqliteStatement& row) {
  ObjectSummary summary;
  summary.id = row.ColumnInt64(0);
  summary.name = row.ColumnText(1);
  summary.variant = VariantFromColumn(row.ColumnText(2), summary.id);
  summary.created_at = row.ColumnText(3);
  summary.updated_at = row.ColumnText(4);
  summary.metadata = row.ColumnText(5);
  summary.view_count = row.ColumnInt64(6);
  return summary;
}

// The descriptor stored in a views row of an object of `variant`; the schema guarantees one of
// the variants' lengths, not the object's nor the values' range.
DescriptorValues DescriptorFromColumn(const SqliteStatement& row, int column, ObjectId object,
                                      DescriptorVariant variant) {
  try {
    return DescriptorFromBytes(row.ColumnBlob(column), variant);
  } catch (const std::invalid_argument& e) {
    throw StoreError(StoreError::Code::kCorrupt,
                     "a view of object " + std::to_string(object) + ": " + e.what());
  }
}

ModelView ViewFromRow(const SqliteStatement& row, int first_column, ObjectId object,
                      DescriptorVariant variant) {
  ModelView view;
  view.azimuth = row.ColumnDouble(first_column);
  if (!row.IsNull(first_column + 1)) view.elevation = row.ColumnDouble(first_column + 1);
  view.descriptor = DescriptorFromColumn(row, first_column + 2, object, variant);
  view.typical_distance = row.ColumnDouble(first_column + 3);
  return view;
}

// Records the size of the write-ahead log after each commit on the writer connection (it replaces
// SQLite's own auto-checkpoint, which CommitWrite takes over).
int OnWalCommit(void* wal_pages, sqlite3*, const char*, int pages) {
  *static_cast<int*>(wal_pages) = pages;
  return SQLITE_OK;
}

// The id of the object named `name` on `connection`, if any.
std::optional<ObjectId> FindId(SqliteConnection& connection, std::string_view name) {
  StatementLease find = connection.Prepare("SELECT id FROM objects WHERE name = ?1");
  find->Bind(1, name);
  if (!find->Step()) return std::nullopt;
  return find->ColumnInt64(0);
}

// The object `id` with its views and thumbnails, read on `connection` (inside the caller's read
// transaction); nullopt when absent.
std::optional<StoredObject> ReadObject(SqliteConnection& connection, ObjectId id) {
  StoredObject object;
  {
    StatementLease find =
        connection.Prepare("SELECT " ORBIT_SUMMARY_COLUMNS " FROM objects o WHERE o.id = ?1");
    find->Bind(1, id);
    if (!find->Step()) return std::nullopt;
    object.summary = SummaryFromRow(*find);
  }
  StatementLease views = connection.Prepare(
      "SELECT azimuth, elevation, descriptor, typical_distance, thumbnail FROM views "
      "WHERE object_id = ?1 ORDER BY azimuth, id");
  views->Bind(1, id);
  while (views->Step()) {
    object.views.push_back(ViewFromRow(*views, 0, id, object.summary.variant));
    const std::span<const std::uint8_t> thumbnail = views->ColumnBlob(4);
    object.thumbnails.emplace_back(thumbnail.begin(), thumbnail.end());
  }
  return object;
}

// Inserts `views` (with `thumbnails`: none, or one per view, "" for none) of object `id` on the
// store's writer connection, inside its write transaction.
void InsertViews(SqliteConnection& writer, ObjectId id, DescriptorVariant variant,
                 const std::vector<ModelView>& views, const std::vector<std::string>& thumbnails) {
  StatementLease insert = writer.Prepare(
      "INSERT INTO views (object_id, azimuth, elevation, descriptor, typical_distance, thumbnail) "
      "VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
  for (std::size_t i = 0; i < views.size(); ++i) {
    const ModelView& view = views[i];
    insert->Bind(1, id);
    insert->Bind(2, NormaliseAzimuth(view.azimuth));
    if (view.elevation) {
      insert->Bind(3, *view.elevation);
    } else {
      insert->BindNull(3);
    }
    insert->BindBlob(4, DescriptorBytes(view.descriptor, variant));
    insert->Bind(5, view.typical_distance);
    if (i < thumbnails.size() && !thumbnails[i].empty()) {
      const std::string& thumbnail = thumbnails[i];
      insert->BindBlob(6,
                       {reinterpret_cast<const std::uint8_t*>(thumbnail.data()), thumbnail.size()});
    } else {
      insert->BindNull(6);
    }
    insert->Run();
    insert->Reset();
  }
}

}  // namespace

// A read connection on loan from the store's pool, for the span of one read (inside the
// checkpoint gate).
class SqliteModelStore::Reader {
 public:
  explicit Reader(SqliteModelStore& store) : store_(store) {
    store_.checkpoint_gate_.EnterRead();
    {
      MutexLock lock(&store_.readers_mutex_);
      if (!store_.idle_readers_.empty()) {
        connection_ = std::move(store_.idle_readers_.back());
        store_.idle_readers_.pop_back();
      }
    }
    try {
      if (!connection_) {
        connection_ = std::make_unique<SqliteConnection>(
            store_.file_, SqliteConnection::Mode::kReadOnly, store_.options_.busy_timeout);
      }
    } catch (...) {
      store_.checkpoint_gate_.LeaveRead();
      throw;
    }
  }
  ~Reader() {
    {
      MutexLock lock(&store_.readers_mutex_);
      if (store_.idle_readers_.size() < kMaxIdleReaders) {
        store_.idle_readers_.push_back(std::move(connection_));
      }
    }
    connection_.reset();  // closed outside the gate's lock, when not kept
    store_.checkpoint_gate_.LeaveRead();
  }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  SqliteConnection& connection() { return *connection_; }

 private:
  SqliteModelStore& store_;
  std::unique_ptr<SqliteConnection> connection_;
};

SqliteModelStore::SqliteModelStore(const std::filesystem::path& file,
                                   const SqliteModelStoreOptions& options)
    : file_(file), options_(options) {
  if (options_.checkpoint_pages < 1) {
    throw std::invalid_argument("checkpoint_pages must be at least 1");
  }
  if (!options_.create_if_missing && !std::filesystem::exists(file_)) {
    throw StoreError(StoreError::Code::kIo, "model store " + file_.string() + " does not exist");
  }
  try {
    // Created here rather than by SQLite, whose files take the umask's mode: the store and its
    // log and shared-memory files (SQLite gives them the database file's mode) are private.
    if (options_.create_if_missing) CreateStoreFile(file_, kStoreFileMode);
    writer_ = std::make_unique<SqliteConnection>(file_,
                                                 options_.create_if_missing
                                                     ? SqliteConnection::Mode::kReadWriteCreate
                                                     : SqliteConnection::Mode::kReadWrite,
                                                 options_.busy_timeout);
    // WAL: readers never block the writer nor the writer the readers, and a commit is one
    // sequential append plus one fsync.
    const std::string journal_mode = writer_->QueryText("PRAGMA journal_mode = WAL");
    if (journal_mode != "wal") {
      throw StoreError(StoreError::Code::kIo,
                       "cannot switch to write-ahead logging (journal mode stays \"" +
                           journal_mode + "\"); the store needs a local file system");
    }
    // FULL: the log is synced at every commit, so an acknowledged write survives power loss
    // (NORMAL would only guarantee consistency).
    writer_->Execute("PRAGMA synchronous = FULL; PRAGMA foreign_keys = ON;");
    if (options_.quick_check_on_open) {
      const std::string verdict = writer_->QueryText("PRAGMA quick_check");
      if (verdict != "ok") {
        throw StoreError(StoreError::Code::kCorrupt, "PRAGMA quick_check failed: " + verdict);
      }
    }
    MigrateSchema(*writer_);
    // When a checkpoint resets the log, the file is cut back to this size (bytes).
    StatementLease limit = writer_->Prepare("PRAGMA journal_size_limit = 4194304");
    limit->Run();
    sqlite3_wal_hook(writer_->handle(), &OnWalCommit, &wal_pages_);
  } catch (const StoreError& e) {
    throw StoreError(e.code(), "cannot open model store " + file_.string() + ": " + e.what());
  }
}

SqliteModelStore::~SqliteModelStore() = default;

ObjectId SqliteModelStore::Enroll(const Enrollment& enrollment) {
  ValidateObjectName(enrollment.name);
  ValidateViews(enrollment.views, enrollment.thumbnails);
  ValidateMetadata(enrollment.metadata);

  MutexLock lock(&write_mutex_);
  SqliteTransaction transaction(*writer_, SqliteTransaction::Mode::kWrite);
  if (const std::optional<ObjectId> owner = FindId(*writer_, enrollment.name)) {
    throw NameTaken(enrollment.name, *owner);
  }
  ObjectId id = 0;
  {
    StatementLease insert = writer_->Prepare(
        std::string("INSERT INTO objects (name, variant, created_at, updated_at, metadata) "
                    "VALUES (?1, ?2, ") +
        kNow + ", " + kNow + ", ?3) RETURNING id");
    insert->Bind(1, std::string_view(enrollment.name));
    insert->Bind(2, VariantName(enrollment.variant));
    insert->Bind(3, std::string_view(enrollment.metadata));
    insert->Step();
    id = insert->ColumnInt64(0);
    insert->Run();  // RETURNING: the row is only written once the statement has run to its end
  }
  InsertViews(*writer_, id, enrollment.variant, enrollment.views, enrollment.thumbnails);
  CommitWrite(transaction);
  return id;
}

void SqliteModelStore::AddViews(ObjectId id, const std::vector<ModelView>& views,
                                const std::vector<std::string>& thumbnails) {
  ValidateViews(views, thumbnails);

  MutexLock lock(&write_mutex_);
  SqliteTransaction transaction(*writer_, SqliteTransaction::Mode::kWrite);
  DescriptorVariant variant{};
  {
    StatementLease count = writer_->Prepare(
        "SELECT (SELECT count(*) FROM views WHERE object_id = ?1), variant FROM objects "
        "WHERE id = ?1");
    count->Bind(1, id);
    if (!count->Step()) throw ObjectNotFound(id);
    const auto existing = static_cast<std::size_t>(count->ColumnInt64(0));
    variant = VariantFromColumn(count->ColumnText(1), id);
    if (existing + views.size() > kMaxViewsPerObject) {
      throw std::invalid_argument(
          "object " + std::to_string(id) + " has " + std::to_string(existing) + " views; " +
          std::to_string(views.size()) + " more would exceed the limit of " +
          std::to_string(kMaxViewsPerObject) + " per object");
    }
  }
  InsertViews(*writer_, id, variant, views, thumbnails);
  {
    StatementLease touch =
        writer_->Prepare(std::string("UPDATE objects SET updated_at = ") + kNow + " WHERE id = ?1");
    touch->Bind(1, id);
    touch->Run();
  }
  CommitWrite(transaction);
}

void SqliteModelStore::Delete(ObjectId id) {
  MutexLock lock(&write_mutex_);
  SqliteTransaction transaction(*writer_, SqliteTransaction::Mode::kWrite);
  {
    // The views go with it: ON DELETE CASCADE (foreign_keys is on).
    StatementLease remove = writer_->Prepare("DELETE FROM objects WHERE id = ?1 RETURNING id");
    remove->Bind(1, id);
    if (!remove->Step()) throw ObjectNotFound(id);
    remove->Run();
  }
  CommitWrite(transaction);
}

void SqliteModelStore::Rename(ObjectId id, std::string_view new_name) {
  ValidateObjectName(new_name);

  MutexLock lock(&write_mutex_);
  SqliteTransaction transaction(*writer_, SqliteTransaction::Mode::kWrite);
  if (const std::optional<ObjectId> owner = FindId(*writer_, new_name)) {
    if (*owner == id) return;  // already so named
    throw NameTaken(new_name, *owner);
  }
  {
    StatementLease rename = writer_->Prepare(std::string("UPDATE objects SET name = ?2, "
                                                         "updated_at = ") +
                                             kNow + " WHERE id = ?1 RETURNING id");
    rename->Bind(1, id);
    rename->Bind(2, new_name);
    if (!rename->Step()) throw ObjectNotFound(id);
    rename->Run();
  }
  CommitWrite(transaction);
}

void SqliteModelStore::CommitWrite(SqliteTransaction& transaction) {
  transaction.Commit();
  if (wal_pages_ < options_.checkpoint_pages) return;
  // Copies the logged pages into the database as far as no reader still needs them; the next
  // write then starts the log again from its beginning. Errors are not the caller's: the write
  // is committed, and a checkpoint that fails now is tried again after the next commit.
  int log_pages = 0;
  int copied_pages = 0;
  const int rc = sqlite3_wal_checkpoint_v2(writer_->handle(), "main", SQLITE_CHECKPOINT_PASSIVE,
                                           &log_pages, &copied_pages);
  if (rc == SQLITE_OK && copied_pages == log_pages) return;
  if (wal_pages_ < kEscalateCheckpointFactor * options_.checkpoint_pages) return;
  // Readers kept the log from being recycled for too long: drain this store's readers, copy
  // everything and cut the log to zero bytes (storage/checkpoint_gate.h has the why).
  sqlite3* const db = writer_->handle();
  checkpoint_gate_.RunExclusive([this, db] {
    sqlite3_busy_timeout(db, static_cast<int>(kCheckpointReaderWait.count()));
    sqlite3_wal_checkpoint_v2(db, "main", SQLITE_CHECKPOINT_TRUNCATE, nullptr, nullptr);
    sqlite3_busy_timeout(db, static_cast<int>(options_.busy_timeout.count()));
  });
}

std::vector<ObjectSummary> SqliteModelStore::List(const ListRequest& request) {
  if (request.limit < 1 || request.limit > kMaxListLimit) {
    throw std::invalid_argument("list limit " + std::to_string(request.limit) + " is outside 1.." +
                                std::to_string(kMaxListLimit));
  }
  Reader reader(*this);
  StatementLease list = reader.connection().Prepare(
      "SELECT " ORBIT_SUMMARY_COLUMNS " FROM objects o WHERE o.id > ?1 ORDER BY o.id LIMIT ?2");
  list->Bind(1, request.after_id);
  list->Bind(2, static_cast<std::int64_t>(request.limit));
  std::vector<ObjectSummary> page;
  while (list->Step()) page.push_back(SummaryFromRow(*list));
  return page;
}

std::optional<StoredObject> SqliteModelStore::Get(ObjectId id) {
  Reader reader(*this);
  SqliteConnection& connection = reader.connection();
  SqliteTransaction snapshot(connection, SqliteTransaction::Mode::kRead);
  return ReadObject(connection, id);
}

std::optional<ObjectSummary> SqliteModelStore::Find(std::string_view name) {
  Reader reader(*this);
  StatementLease find = reader.connection().Prepare("SELECT " ORBIT_SUMMARY_COLUMNS
                                                    " FROM objects o WHERE o.name = ?1");
  find->Bind(1, name);
  if (!find->Step()) return std::nullopt;
  return SummaryFromRow(*find);
}

std::vector<ObjectModel> SqliteModelStore::LoadAll() {
  Reader reader(*this);
  SqliteConnection& connection = reader.connection();
  SqliteTransaction snapshot(connection, SqliteTransaction::Mode::kRead);
  std::vector<ObjectModel> models;
  std::unordered_map<ObjectId, std::size_t> position;  // object id -> index in models
  {
    StatementLease objects =
        connection.Prepare("SELECT id, name, variant FROM objects ORDER BY id");
    while (objects->Step()) {
      ObjectModel& model = models.emplace_back();
      model.id = objects->ColumnInt64(0);
      model.name = objects->ColumnText(1);
      model.variant = VariantFromColumn(objects->ColumnText(2), model.id);
      position.emplace(model.id, models.size() - 1);
    }
  }
  {
    // One pass over the table in storage order: faster than one index lookup per object. The
    // foreign key guarantees every view's object was read above, in the same snapshot.
    StatementLease views = connection.Prepare(
        "SELECT object_id, azimuth, elevation, descriptor, typical_distance FROM views "
        "ORDER BY id");
    while (views->Step()) {
      const ObjectId object = views->ColumnInt64(0);
      ObjectModel& model = models[position.at(object)];
      model.views.push_back(ViewFromRow(*views, 1, object, model.variant));
    }
  }
  for (ObjectModel& model : models) {
    std::stable_sort(model.views.begin(), model.views.end(),
                     [](const ModelView& a, const ModelView& b) { return a.azimuth < b.azimuth; });
  }
  return models;
}

ObjectId SqliteModelStore::ForEachObject(const std::function<void(const StoredObject&)>& visit) {
  Reader reader(*this);
  SqliteConnection& connection = reader.connection();
  SqliteTransaction snapshot(connection, SqliteTransaction::Mode::kRead);
  std::vector<ObjectId> ids;
  {
    StatementLease list = connection.Prepare("SELECT id FROM objects ORDER BY id");
    while (list->Step()) ids.push_back(list->ColumnInt64(0));
  }
  // Every id read above is in the snapshot, so each object is there, whole.
  for (const ObjectId id : ids) visit(*ReadObject(connection, id));
  StatementLease highest = connection.Prepare(
      "SELECT coalesce((SELECT seq FROM sqlite_sequence WHERE name = 'objects'), 0)");
  highest->Step();
  return highest->ColumnInt64(0);
}

void SqliteModelStore::RestoreFrom(ModelStore& source) {
  MutexLock lock(&write_mutex_);
  SqliteTransaction transaction(*writer_, SqliteTransaction::Mode::kWrite);
  SqliteConnection& writer = *writer_;  // for the visitor, which runs under this lock
  if (const std::int64_t count = std::stoll(writer.QueryText("SELECT count(*) FROM objects"));
      count > 0) {
    throw StoreNotEmpty(file_.string(), count);
  }
  const ObjectId highest = source.ForEachObject([&writer](const StoredObject& object) {
    ValidateStoredObject(object);
    const ObjectSummary& summary = object.summary;
    {
      StatementLease insert = writer.Prepare(
          "INSERT INTO objects (id, name, variant, created_at, updated_at, metadata) "
          "VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
      insert->Bind(1, summary.id);
      insert->Bind(2, std::string_view(summary.name));
      insert->Bind(3, VariantName(summary.variant));
      insert->Bind(4, std::string_view(summary.created_at));
      insert->Bind(5, std::string_view(summary.updated_at));
      insert->Bind(6, std::string_view(summary.metadata));
      insert->Run();
    }
    InsertViews(writer, summary.id, summary.variant, object.views, object.thumbnails);
  });
  // AUTOINCREMENT's high-water mark: at least the source's, so no id it handed out comes back.
  {
    StatementLease raise =
        writer.Prepare("UPDATE sqlite_sequence SET seq = ?1 WHERE name = 'objects' AND seq < ?1");
    raise->Bind(1, highest);
    raise->Run();
  }
  {
    StatementLease first = writer.Prepare(
        "INSERT INTO sqlite_sequence (name, seq) SELECT 'objects', ?1 "
        "WHERE ?1 > 0 AND NOT EXISTS (SELECT 1 FROM sqlite_sequence WHERE name = 'objects')");
    first->Bind(1, highest);
    first->Run();
  }
  CommitWrite(transaction);
}

void SqliteModelStore::Backup(const std::filesystem::path& destination) {
  std::error_code ignored;
  if (std::filesystem::equivalent(destination, file_, ignored)) {
    throw std::invalid_argument("backup destination " + destination.string() +
                                " is the model store itself");
  }
  // The copy holds what the store holds: no one may read it who may not read the store.
  const std::filesystem::file_status status = std::filesystem::status(file_, ignored);
  const std::filesystem::perms mode =
      std::filesystem::exists(status) ? status.permissions() : kStoreFileMode;
  WriteStoreCopy(file_.string(), destination, mode, [this](const std::filesystem::path& partial) {
    SqliteConnection copy(partial, SqliteConnection::Mode::kReadWrite, options_.busy_timeout);
    Reader reader(*this);
    sqlite3_backup* backup =
        sqlite3_backup_init(copy.handle(), "main", reader.connection().handle(), "main");
    if (backup == nullptr) {
      throw SqliteError(sqlite3_errcode(copy.handle()), copy.handle(), "cannot start backup");
    }
    // All pages in one step: the source stays in one read transaction (one snapshot) for the
    // whole copy, while writers carry on in the write-ahead log.
    const int step = sqlite3_backup_step(backup, -1);
    const int finish = sqlite3_backup_finish(backup);
    if (step != SQLITE_DONE) throw SqliteError(step, nullptr, "backup failed");
    if (finish != SQLITE_OK) throw SqliteError(finish, copy.handle(), "backup failed");
  });
}

}  // namespace orbit
