#include "client/models_client.h"

#include "client/rpc_error.h"

namespace orbit {

v1::ObjectRef ObjectById(std::int64_t id) {
  v1::ObjectRef ref;
  ref.set_id(id);
  return ref;
}

v1::ObjectRef ObjectByName(const std::string& name) {
  v1::ObjectRef ref;
  ref.set_name(name);
  return ref;
}

ModelsClient::ModelsClient(const Connection& connection)
    : connection_(connection), stub_(v1::Models::NewStub(connection.channel())) {}

v1::ServerInfoResponse ModelsClient::ServerInfo() {
  grpc::ClientContext context;
  connection_.PrepareUnaryCall(context);
  v1::ServerInfoResponse response;
  ThrowIfError("ServerInfo", stub_->ServerInfo(&context, v1::ServerInfoRequest(), &response));
  return response;
}

v1::ListObjectsResponse ModelsClient::ListObjects(int page_size, const std::string& page_token) {
  grpc::ClientContext context;
  connection_.PrepareUnaryCall(context);
  v1::ListObjectsRequest request;
  request.set_page_size(page_size);
  request.set_page_token(page_token);
  v1::ListObjectsResponse response;
  ThrowIfError("ListObjects", stub_->ListObjects(&context, request, &response));
  return response;
}

std::vector<v1::ObjectInfo> ModelsClient::ListAllObjects() {
  std::vector<v1::ObjectInfo> objects;
  std::string token;
  do {
    v1::ListObjectsResponse page = ListObjects(1000, token);
    for (v1::ObjectInfo& object : *page.mutable_objects()) objects.push_back(std::move(object));
    token = page.next_page_token();
  } while (!token.empty());
  return objects;
}

v1::GetObjectResponse ModelsClient::GetObject(const v1::ObjectRef& object, bool include_views) {
  v1::GetObjectRequest request;
  *request.mutable_object() = object;
  request.set_include_views(include_views);
  v1::GetObjectResponse whole;
  do {
    grpc::ClientContext context;
    connection_.PrepareUnaryCall(context);
    v1::GetObjectResponse page;
    ThrowIfError("GetObject", stub_->GetObject(&context, request, &page));
    *whole.mutable_object() = page.object();
    for (v1::View& view : *page.mutable_views()) *whole.add_views() = std::move(view);
    request.set_view_offset(page.next_view_offset());
  } while (request.view_offset() > 0);
  return whole;
}

v1::ObjectInfo ModelsClient::DeleteObject(const v1::ObjectRef& object) {
  grpc::ClientContext context;
  connection_.PrepareUnaryCall(context);
  v1::DeleteObjectRequest request;
  *request.mutable_object() = object;
  v1::DeleteObjectResponse response;
  ThrowIfError("DeleteObject", stub_->DeleteObject(&context, request, &response));
  return response.deleted();
}

v1::ObjectInfo ModelsClient::AddViews(const v1::ObjectRef& object,
                                      const std::vector<v1::View>& views) {
  grpc::ClientContext context;
  connection_.PrepareUnaryCall(context);
  v1::AddViewsRequest request;
  *request.mutable_object() = object;
  for (const v1::View& view : views) *request.add_views() = view;
  v1::ObjectInfo response;
  ThrowIfError("AddViews", stub_->AddViews(&context, request, &response));
  return response;
}

}  // namespace orbit
