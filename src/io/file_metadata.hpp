// What a file says about itself, carried from its reader to a writer as one JSON object (Scene::extrasJson):
// glTF's asset.extras (an exporter's author, licence, source and title), X3D's <head> <meta> tags. symcompress's
// digest of the original is one member of it, which only a writer's options give (WriteOptions::extrasJson): a
// file written from a scene describes that scene, not the one a digest read with it was made from.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace symcompress {

// The member that holds symcompress's digest (SurfaceDigest::json).
inline constexpr const char* kDigestMember = "symcompress_digest";

// The object a writer writes: the scene's members but the digest, then those of `writerExtras`. Null where
// both have none. Throws std::invalid_argument where `writerExtras` is not a JSON object.
nlohmann::json writtenExtras(const std::string& sceneExtras, const std::string& writerExtras);

// An X3D meta tag as a member of such an object: a name given twice holds an array of its contents.
void addMetaTag(nlohmann::json& extras, const std::string& name, const std::string& content);

// Of a glTF extensions object (JSON text), the members that symcompress passes through as they are, wherever it keeps
// the object they are on (the file, its asset, its scene, a node): those whose indices name only what the file's
// own object of them holds (KHR_xmp_json_ld's packets). JSON text, empty for none.
std::string passedThroughExtensions(const std::string& extensionsJson);

// The digest (an array of numbers) as an X3D meta tag's content, its numbers apart by spaces, and back (null
// where the content is anything else): a tag of its own, not JSON in an attribute, whose quotes XML escapes.
std::string digestAsMetaContent(const nlohmann::json& digest);
nlohmann::json digestFromMetaContent(const std::string& content);

// Such an object's members as X3D meta tags (name, content), the digest's left out: a string as it is, an array
// a tag for each of its strings, anything else as its JSON text.
std::vector<std::pair<std::string, std::string>> metaTags(const nlohmann::json& extras);

}  // namespace symcompress
