#include "web/static_assets.hpp"

#include <algorithm>
#include <cctype>
#include <string>

namespace armctl::web {

const StaticAsset* find_asset(std::string_view path) {
  if (path == "/") path = "/index.html";
  for (const auto& a : static_assets())
    if (path == a.path) return &a;
  return nullptr;
}

const char* content_type_for(std::string_view path) {
  struct Type {
    const char* extension;
    const char* type;
  };
  static constexpr Type kTypes[] = {
      {".html", "text/html; charset=utf-8"},     {".htm", "text/html; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"}, {".mjs", "text/javascript; charset=utf-8"},
      {".css", "text/css; charset=utf-8"},       {".json", "application/json"},
      {".map", "application/json"},              {".svg", "image/svg+xml"},
      {".png", "image/png"},                     {".jpg", "image/jpeg"},
      {".jpeg", "image/jpeg"},                   {".gif", "image/gif"},
      {".ico", "image/x-icon"},                  {".webp", "image/webp"},
      {".woff", "font/woff"},                    {".woff2", "font/woff2"},
      {".ttf", "font/ttf"},                      {".txt", "text/plain; charset=utf-8"},
      {".wasm", "application/wasm"},             {".xml", "application/xml"},
      {".urdf", "application/xml"},              {".stl", "model/stl"},
      {".glb", "model/gltf-binary"},             {".gltf", "model/gltf+json"},
  };
  const auto slash = path.rfind('/');
  const auto dot = path.rfind('.');
  if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash))
    return "application/octet-stream";
  std::string ext(path.substr(dot));
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const auto& t : kTypes)
    if (ext == t.extension) return t.type;
  return "application/octet-stream";
}

}  // namespace armctl::web
