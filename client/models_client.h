// ModelsClient: the operator's calls of the Models service (proto/orbit/v1/models.proto) other
// than enrollment (client/enroller.h): server info, listing, inspecting, deleting objects and
// adding views.
//
// Every call has the connection's unary deadline and token, and throws RpcError with the
// server's status on failure (NOT_FOUND for an unknown object, PERMISSION_DENIED for a
// `recognize` token deleting, DEADLINE_EXCEEDED or UNAVAILABLE for an unreachable server).
// Thread-safe: calls may be made from several threads at once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "api/conversion.h"
#include "client/connection.h"
#include "core/descriptor/descriptor.h"
#include "orbit/v1/models.grpc.pb.h"

namespace orbit {

v1::ObjectRef ObjectById(std::int64_t id);
v1::ObjectRef ObjectByName(const std::string& name);

class ModelsClient {
 public:
  // `connection` must outlive the client.
  explicit ModelsClient(const Connection& connection);

  // Version, descriptor variant, object and view counts, session defaults and limits.
  v1::ServerInfoResponse ServerInfo();

  // One page of objects ordered by id; page_token "" for the first page.
  v1::ListObjectsResponse ListObjects(int page_size = 100, const std::string& page_token = "");

  // Every object, following the pages.
  std::vector<v1::ObjectInfo> ListAllObjects();

  // With include_views, every view, following the server's pages (GetObjectResponse).
  v1::GetObjectResponse GetObject(const v1::ObjectRef& object, bool include_views = false);

  // Returns the deleted object's summary.
  v1::ObjectInfo DeleteObject(const v1::ObjectRef& object);

  // Adds views (all or nothing); returns the updated summary. Views with `cedd` should carry
  // their typical distance (client/enroller.h, ComputeView).
  v1::ObjectInfo AddViews(const v1::ObjectRef& object, const std::vector<v1::View>& views);

 private:
  const Connection& connection_;
  std::unique_ptr<v1::Models::Stub> stub_;
};

}  // namespace orbit
