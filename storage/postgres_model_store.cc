#include "storage/postgres_model_store.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "core/base/angles.h"
#include "storage/model_validation.h"
#include "storage/postgres_connection.h"
#include "storage/postgres_schema.h"
#include "storage/postgres_transaction.h"
#include "storage/sqlite_model_store.h"
#include "storage/store_copy.h"
#include "storage/store_error.h"
#include "storage/store_files.h"

namespace orbit {
namespace {

// A timestamptz column as ObjectSummary's text: UTC, ISO 8601 with milliseconds.
#define ORBIT_PG_TIME(column) \
  "to_char(" column " AT TIME ZONE 'UTC', 'YYYY-MM-DD\"T\"HH24:MI:SS.MS\"Z\"')"

// The columns SummaryFromRow reads, in order.
#define ORBIT_PG_SUMMARY_COLUMNS \
  "o.id, o.name, o.variant, " ORBIT_PG_TIME("o.created_at") ", "        \
      ORBIT_PG_TIME("o.updated_at") ", o.metadata, "                    \
      "(SELECT count(*) FROM views v WHERE v.object_id = o.id)"

DescriptorVariant VariantFromColumn(const std::string& text, ObjectId id) {
  const std::optional<DescriptorVariant> variant = ParseVariant(text);
  if (!variant) {
    throw StoreError(
        StoreError::Code::kCorrupt,
        "object " + std::to_string(id) + " has an unknown descriptor variant \"" + text + "\"");
  }
  return *variant;
}

ObjectSummary SummaryFromRow(const PostgresResult& rows, int row) {
  ObjectSummary summary;
  summary.id = rows.Int64(row, 0);
  summary.name = rows.Text(row, 1);
  summary.variant = VariantFromColumn(rows.Text(row, 2), summary.id);
  summary.created_at = rows.Text(row, 3);
  summary.updated_at = rows.Text(row, 4);
  summary.metadata = rows.Text(row, 5);
  summary.view_count = rows.Int64(row, 6);
  return summary;
}

// The view in columns first_column.. of `row`: azimuth, elevation, descriptor, typical distance.
ModelView ViewFromRow(const PostgresResult& rows, int row, int first_column, ObjectId object,
                      DescriptorVariant variant) {
  ModelView view;
  view.azimuth = rows.Double(row, first_column);
  if (!rows.IsNull(row, first_column + 1)) view.elevation = rows.Double(row, first_column + 1);
  const std::string descriptor = rows.Bytes(row, first_column + 2);
  try {
    view.descriptor = DescriptorFromBytes(
        {reinterpret_cast<const std::uint8_t*>(descriptor.data()), descriptor.size()}, variant);
  } catch (const std::invalid_argument& e) {
    throw StoreError(StoreError::Code::kCorrupt,
                     "a view of object " + std::to_string(object) + ": " + e.what());
  }
  view.typical_distance = rows.Double(row, first_column + 3);
  return view;
}

// The id of the object named `name`, if any.
std::optional<ObjectId> FindId(PostgresConnection& connection, std::string_view name) {
  const PostgresResult found =
      connection.Query("SELECT id FROM objects WHERE name = $1", PostgresParams().Add(name));
  if (found.rows() == 0) return std::nullopt;
  return found.Int64(0, 0);
}

// Inserts `views` (with `thumbnails`: none, or one per view, "" for none) of object `id`, inside
// the caller's write transaction.
void InsertViews(PostgresConnection& connection, ObjectId id, DescriptorVariant variant,
                 const std::vector<ModelView>& views, const std::vector<std::string>& thumbnails) {
  // One statement for all the views (at most kMaxViewsPerObject x 6 parameters, far below
  // PostgreSQL's 65535): one round trip, however many views.
  constexpr int kColumns = 6;
  std::string sql =
      "INSERT INTO views (object_id, azimuth, elevation, descriptor, typical_distance, "
      "thumbnail) VALUES ";
  PostgresParams params;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const ModelView& view = views[i];
    const int first = static_cast<int>(i) * kColumns + 1;
    sql += i == 0 ? "(" : ", (";
    for (int c = 0; c < kColumns; ++c) sql += (c == 0 ? "$" : ", $") + std::to_string(first + c);
    sql += ")";
    params.Add(id).Add(NormaliseAzimuth(view.azimuth));
    if (view.elevation) {
      params.Add(*view.elevation);
    } else {
      params.AddNull();
    }
    params.AddBytes(DescriptorBytes(view.descriptor, variant)).Add(view.typical_distance);
    if (i < thumbnails.size() && !thumbnails[i].empty()) {
      const std::string& thumbnail = thumbnails[i];
      params.AddBytes({reinterpret_cast<const std::uint8_t*>(thumbnail.data()), thumbnail.size()});
    } else {
      params.AddNull();
    }
  }
  connection.Query(sql, params);
}

// The object `id` with its views and thumbnails, read on `connection` (inside the caller's
// snapshot); nullopt when absent.
std::optional<StoredObject> ReadObject(PostgresConnection& connection, ObjectId id) {
  const PostgresResult found =
      connection.Query("SELECT " ORBIT_PG_SUMMARY_COLUMNS " FROM objects o WHERE o.id = $1",
                       PostgresParams().Add(id));
  if (found.rows() == 0) return std::nullopt;
  StoredObject object;
  object.summary = SummaryFromRow(found, 0);
  const PostgresResult views = connection.Query(
      "SELECT azimuth, elevation, descriptor, typical_distance, thumbnail FROM views "
      "WHERE object_id = $1 ORDER BY azimuth, id",
      PostgresParams().Add(id));
  for (int row = 0; row < views.rows(); ++row) {
    object.views.push_back(ViewFromRow(views, row, 0, id, object.summary.variant));
    object.thumbnails.push_back(views.Bytes(row, 4));
  }
  return object;
}

// Appends the change to the log and tells the listeners, in the caller's write transaction (the
// notification is delivered when it commits).
void RecordChange(PostgresConnection& connection, ObjectId id, ModelChangeKind kind) {
  connection.Query(std::string("WITH change AS (INSERT INTO model_changes (object_id, kind) "
                               "VALUES ($1, $2) RETURNING seq) "
                               "SELECT pg_notify('") +
                       kModelChangesChannel + "', seq::text) FROM change",
                   PostgresParams().Add(id).Add(ModelChangeKindName(kind)));
}

}  // namespace

// A connection on loan from the store's pool for the span of one call; back to the pool when
// it is fit for reuse (up, outside any transaction), closed otherwise.
class PostgresModelStore::Lease {
 public:
  explicit Lease(PostgresModelStore& store) : store_(store) {
    for (;;) {
      {
        MutexLock lock(&store_.pool_mutex_);
        if (store_.idle_.empty()) break;
        connection_ = std::move(store_.idle_.back());
        store_.idle_.pop_back();
      }
      if (connection_->StillOpen()) break;
      connection_.reset();  // closed by the server while idle (a restart): try the next
    }
    if (!connection_) {
      connection_ = std::make_unique<PostgresConnection>(store_.conninfo_,
                                                         store_.options_.busy_timeout.count());
    }
  }
  ~Lease() {
    if (!connection_->Reusable()) return;  // closed here; the next call connects afresh
    MutexLock lock(&store_.pool_mutex_);
    if (store_.idle_.size() < static_cast<std::size_t>(store_.options_.max_idle_connections)) {
      store_.idle_.push_back(std::move(connection_));
    }
  }
  Lease(const Lease&) = delete;
  Lease& operator=(const Lease&) = delete;

  PostgresConnection& operator*() const { return *connection_; }

 private:
  PostgresModelStore& store_;
  std::unique_ptr<PostgresConnection> connection_;
};

PostgresModelStore::PostgresModelStore(const std::string& conninfo,
                                       const PostgresModelStoreOptions& options)
    : conninfo_(conninfo), target_(RedactedTarget(conninfo)), options_(options) {
  if (options_.max_idle_connections < 0) {
    throw std::invalid_argument("max_idle_connections must not be negative");
  }
  try {
    Lease lease(*this);
    MigratePostgresSchema(*lease);
  } catch (const StoreError& e) {
    // Most messages name the target already ("cannot connect to PostgreSQL <target>: ...").
    const std::string what = e.what();
    throw StoreError(e.code(), what.find(target_) != std::string::npos
                                   ? "cannot open model store: " + what
                                   : "cannot open model store " + target_ + ": " + what);
  }
}

PostgresModelStore::~PostgresModelStore() = default;

ObjectId PostgresModelStore::Enroll(const Enrollment& enrollment) {
  ValidateObjectName(enrollment.name);
  ValidateViews(enrollment.views, enrollment.thumbnails);
  ValidateMetadata(enrollment.metadata);

  MutexLock lock(&write_mutex_);
  Lease lease(*this);
  PostgresConnection& connection = *lease;
  PostgresTransaction transaction(connection, PostgresTransaction::Mode::kWrite);
  if (const std::optional<ObjectId> owner = FindId(connection, enrollment.name)) {
    throw NameTaken(enrollment.name, *owner);
  }
  const ObjectId id =
      connection
          .Query(
              "INSERT INTO objects (name, variant, created_at, updated_at, metadata) "
              "VALUES ($1, $2, now(), now(), $3) RETURNING id",
              PostgresParams()
                  .Add(std::string_view(enrollment.name))
                  .Add(VariantName(enrollment.variant))
                  .Add(std::string_view(enrollment.metadata)))
          .Int64(0, 0);
  InsertViews(connection, id, enrollment.variant, enrollment.views, enrollment.thumbnails);
  RecordChange(connection, id, ModelChangeKind::kEnroll);
  transaction.Commit();
  return id;
}

void PostgresModelStore::AddViews(ObjectId id, const std::vector<ModelView>& views,
                                  const std::vector<std::string>& thumbnails) {
  ValidateViews(views, thumbnails);

  MutexLock lock(&write_mutex_);
  Lease lease(*this);
  PostgresConnection& connection = *lease;
  PostgresTransaction transaction(connection, PostgresTransaction::Mode::kWrite);
  const PostgresResult count = connection.Query(
      "SELECT (SELECT count(*) FROM views WHERE object_id = $1), variant FROM objects "
      "WHERE id = $1",
      PostgresParams().Add(id));
  if (count.rows() == 0) throw ObjectNotFound(id);
  const DescriptorVariant variant = VariantFromColumn(count.Text(0, 1), id);
  const auto existing = static_cast<std::size_t>(count.Int64(0, 0));
  if (existing + views.size() > kMaxViewsPerObject) {
    throw std::invalid_argument("object " + std::to_string(id) + " has " +
                                std::to_string(existing) + " views; " +
                                std::to_string(views.size()) + " more would exceed the limit of " +
                                std::to_string(kMaxViewsPerObject) + " per object");
  }
  InsertViews(connection, id, variant, views, thumbnails);
  connection.Query("UPDATE objects SET updated_at = now() WHERE id = $1", PostgresParams().Add(id));
  RecordChange(connection, id, ModelChangeKind::kAddViews);
  transaction.Commit();
}

void PostgresModelStore::Delete(ObjectId id) {
  MutexLock lock(&write_mutex_);
  Lease lease(*this);
  PostgresConnection& connection = *lease;
  PostgresTransaction transaction(connection, PostgresTransaction::Mode::kWrite);
  // The views go with it: ON DELETE CASCADE.
  if (connection.Query("DELETE FROM objects WHERE id = $1 RETURNING id", PostgresParams().Add(id))
          .rows() == 0) {
    throw ObjectNotFound(id);
  }
  RecordChange(connection, id, ModelChangeKind::kDelete);
  transaction.Commit();
}

void PostgresModelStore::Rename(ObjectId id, std::string_view new_name) {
  ValidateObjectName(new_name);

  MutexLock lock(&write_mutex_);
  Lease lease(*this);
  PostgresConnection& connection = *lease;
  PostgresTransaction transaction(connection, PostgresTransaction::Mode::kWrite);
  if (const std::optional<ObjectId> owner = FindId(connection, new_name)) {
    if (*owner == id) return;  // already so named: nothing written, nothing logged
    throw NameTaken(new_name, *owner);
  }
  if (connection
          .Query("UPDATE objects SET name = $2, updated_at = now() WHERE id = $1 RETURNING id",
                 PostgresParams().Add(id).Add(new_name))
          .rows() == 0) {
    throw ObjectNotFound(id);
  }
  RecordChange(connection, id, ModelChangeKind::kRename);
  transaction.Commit();
}

std::vector<ObjectSummary> PostgresModelStore::List(const ListRequest& request) {
  if (request.limit < 1 || request.limit > kMaxListLimit) {
    throw std::invalid_argument("list limit " + std::to_string(request.limit) + " is outside 1.." +
                                std::to_string(kMaxListLimit));
  }
  Lease lease(*this);
  // One statement, one snapshot; pages continue after the last id given, so no object is
  // listed twice and none present throughout is skipped.
  const PostgresResult rows = (*lease).Query(
      "SELECT " ORBIT_PG_SUMMARY_COLUMNS " FROM objects o WHERE o.id > $1 ORDER BY o.id LIMIT $2",
      PostgresParams().Add(request.after_id).Add(std::int64_t{request.limit}));
  std::vector<ObjectSummary> page;
  for (int row = 0; row < rows.rows(); ++row) page.push_back(SummaryFromRow(rows, row));
  return page;
}

std::optional<StoredObject> PostgresModelStore::Get(ObjectId id) {
  Lease lease(*this);
  PostgresConnection& connection = *lease;
  PostgresTransaction snapshot(connection, PostgresTransaction::Mode::kSnapshot);
  std::optional<StoredObject> object = ReadObject(connection, id);
  snapshot.Commit();
  return object;
}

std::optional<ObjectSummary> PostgresModelStore::Find(std::string_view name) {
  Lease lease(*this);
  const PostgresResult found =
      (*lease).Query("SELECT " ORBIT_PG_SUMMARY_COLUMNS " FROM objects o WHERE o.name = $1",
                     PostgresParams().Add(name));
  if (found.rows() == 0) return std::nullopt;
  return SummaryFromRow(found, 0);
}

std::vector<ObjectModel> PostgresModelStore::LoadAll() {
  Lease lease(*this);
  PostgresConnection& connection = *lease;
  PostgresTransaction snapshot(connection, PostgresTransaction::Mode::kSnapshot);
  std::vector<ObjectModel> models;
  std::unordered_map<ObjectId, std::size_t> position;  // object id -> index in models
  {
    const PostgresResult objects =
        connection.Query("SELECT id, name, variant FROM objects ORDER BY id");
    models.reserve(objects.rows());
    for (int row = 0; row < objects.rows(); ++row) {
      ObjectModel& model = models.emplace_back();
      model.id = objects.Int64(row, 0);
      model.name = objects.Text(row, 1);
      model.variant = VariantFromColumn(objects.Text(row, 2), model.id);
      position.emplace(model.id, models.size() - 1);
    }
  }
  {
    // Ordered as Get orders them; the snapshot guarantees every view's object was read above.
    const PostgresResult views = connection.Query(
        "SELECT object_id, azimuth, elevation, descriptor, typical_distance FROM views "
        "ORDER BY object_id, azimuth, id");
    for (int row = 0; row < views.rows(); ++row) {
      const ObjectId object = views.Int64(row, 0);
      ObjectModel& model = models[position.at(object)];
      model.views.push_back(ViewFromRow(views, row, 1, object, model.variant));
    }
  }
  snapshot.Commit();
  return models;
}

ObjectId PostgresModelStore::ForEachObject(const std::function<void(const StoredObject&)>& visit) {
  Lease lease(*this);
  PostgresConnection& connection = *lease;
  PostgresTransaction snapshot(connection, PostgresTransaction::Mode::kSnapshot);
  const PostgresResult ids = connection.Query("SELECT id FROM objects ORDER BY id");
  // Every id read above is in the snapshot, so each object is there, whole.
  for (int row = 0; row < ids.rows(); ++row) visit(*ReadObject(connection, ids.Int64(row, 0)));
  // Sequences stand outside transactions: this is the latest value, at least the snapshot's.
  const ObjectId highest = connection
                               .Query(
                                   "SELECT coalesce(pg_sequence_last_value("
                                   "pg_get_serial_sequence('objects', 'id')::regclass), 0)")
                               .Int64(0, 0);
  snapshot.Commit();
  return highest;
}

void PostgresModelStore::RestoreFrom(ModelStore& source) {
  MutexLock lock(&write_mutex_);
  Lease lease(*this);
  PostgresConnection& connection = *lease;
  PostgresTransaction transaction(connection, PostgresTransaction::Mode::kWrite);
  if (const std::int64_t count = connection.Query("SELECT count(*) FROM objects").Int64(0, 0);
      count > 0) {
    throw StoreNotEmpty(target_, count);
  }
  const ObjectId highest = source.ForEachObject([&connection](const StoredObject& object) {
    ValidateStoredObject(object);
    const ObjectSummary& summary = object.summary;
    connection.Query(
        "INSERT INTO objects (id, name, variant, created_at, updated_at, metadata) "
        "OVERRIDING SYSTEM VALUE VALUES ($1, $2, $3, $4::timestamptz, $5::timestamptz, $6)",
        PostgresParams()
            .Add(summary.id)
            .Add(std::string_view(summary.name))
            .Add(VariantName(summary.variant))
            .Add(std::string_view(summary.created_at))
            .Add(std::string_view(summary.updated_at))
            .Add(std::string_view(summary.metadata)));
    InsertViews(connection, summary.id, summary.variant, object.views, object.thumbnails);
    RecordChange(connection, summary.id, ModelChangeKind::kEnroll);
  });
  // The identity's next value comes after every id the source handed out and every id here.
  connection.Query(
      "SELECT setval(sequence, next_after) FROM ("
      "SELECT pg_get_serial_sequence('objects', 'id') AS sequence, greatest($1::bigint, "
      "(SELECT coalesce(max(id), 0) FROM objects), coalesce(pg_sequence_last_value("
      "pg_get_serial_sequence('objects', 'id')::regclass), 0)) AS next_after) s "
      "WHERE next_after > 0",
      PostgresParams().Add(highest));
  transaction.Commit();
}

void PostgresModelStore::Backup(const std::filesystem::path& destination) {
  WriteStoreCopy(target_, destination, kStoreFileMode, [this](const std::filesystem::path& copy) {
    SqliteModelStore(copy).RestoreFrom(*this);
  });
}

std::vector<ModelChange> PostgresModelStore::ChangesAfter(std::int64_t after_seq, int limit) {
  if (limit < 1 || limit > kMaxListLimit) {
    throw std::invalid_argument("change limit " + std::to_string(limit) + " is outside 1.." +
                                std::to_string(kMaxListLimit));
  }
  Lease lease(*this);
  // One statement, one snapshot: the pruned point and the changes after `after_seq` agree. The
  // first row always exists (the horizon's); its change columns are NULL when there is none.
  const PostgresResult rows = (*lease).Query(
      "SELECT c.seq, c.object_id, c.kind, c.committed_at, h.pruned_through "
      "FROM change_log_horizon h LEFT JOIN LATERAL ("
      "SELECT seq, object_id, kind, " ORBIT_PG_TIME("committed_at") " AS committed_at "
      "FROM model_changes WHERE seq > $1 ORDER BY seq LIMIT $2) c ON true ORDER BY c.seq",
      PostgresParams().Add(after_seq).Add(std::int64_t{limit}));
  if (const std::int64_t pruned_through = rows.Int64(0, 4); pruned_through > after_seq) {
    throw ChangeLogPruned(after_seq, pruned_through);
  }
  std::vector<ModelChange> changes;
  for (int row = 0; row < rows.rows() && !rows.IsNull(row, 0); ++row) {
    const std::optional<ModelChangeKind> kind = ParseModelChangeKind(rows.Text(row, 2));
    if (!kind) {
      throw StoreError(
          StoreError::Code::kCorrupt,
          "change " + rows.Text(row, 0) + " has an unknown kind \"" + rows.Text(row, 2) + "\"");
    }
    changes.push_back({.seq = rows.Int64(row, 0),
                       .object_id = rows.Int64(row, 1),
                       .kind = *kind,
                       .committed_at = rows.Text(row, 3)});
  }
  return changes;
}

std::int64_t PostgresModelStore::LatestChangeSeq() {
  Lease lease(*this);
  return (*lease)
      .Query(
          "SELECT greatest((SELECT coalesce(max(seq), 0) FROM model_changes), "
          "(SELECT pruned_through FROM change_log_horizon))")
      .Int64(0, 0);
}

void PostgresModelStore::ReportApplied(std::string_view replica, std::int64_t applied_seq) {
  Lease lease(*this);
  (*lease).Query(
      "INSERT INTO replica_progress (replica, applied_seq, reported_at) VALUES ($1, $2, now()) "
      "ON CONFLICT (replica) DO UPDATE SET applied_seq = excluded.applied_seq, "
      "reported_at = excluded.reported_at",
      PostgresParams().Add(replica).Add(applied_seq));
}

std::int64_t PostgresModelStore::PruneChanges(std::chrono::milliseconds lease) {
  Lease connection(*this);
  // Every part sees the same snapshot, so `bound` counts the live replicas as they were before
  // `forgotten` deletes the silent ones. A replica reporting meanwhile is not counted: if the
  // bound passes it, it is told so by ChangesAfter, never left with a hole.
  return (*connection)
      .Query(
          "WITH live AS (SELECT now() - $1::bigint * interval '1 millisecond' AS since), "
          "forgotten AS (DELETE FROM replica_progress WHERE reported_at < (SELECT since FROM "
          "live)), "
          "bound AS (SELECT min(applied_seq) AS seq FROM replica_progress "
          "WHERE reported_at >= (SELECT since FROM live)), "
          "pruned AS (DELETE FROM model_changes WHERE seq <= (SELECT seq FROM bound)), "
          "horizon AS (UPDATE change_log_horizon "
          "SET pruned_through = greatest(pruned_through, (SELECT seq FROM bound)) "
          "WHERE (SELECT seq FROM bound) IS NOT NULL RETURNING pruned_through) "
          "SELECT coalesce((SELECT pruned_through FROM horizon), "
          "(SELECT pruned_through FROM change_log_horizon))",
          PostgresParams().Add(std::int64_t{lease.count()}))
      .Int64(0, 0);
}

}  // namespace orbit
