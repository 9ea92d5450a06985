#pragma once
// XML for the VTK files this layer writes (.vtp, .pvd): a parsed document (pugixml, Debian's
// libpugixml-dev) whose errors name the file, the line and the byte offset, and an escaping
// helper for the writers.
#include <pugixml.hpp>
#include <string>
#include <string_view>

namespace invasim {

// The deepest element nesting a document may have. invasim's files nest 5 levels
// (VTKFile/PolyData/Piece/PointData/DataArray); the limit keeps every walk over the tree (ours
// and the library's) far from any stack limit, whatever a hostile file holds.
inline constexpr int kMaxXmlDepth = 64;

// A parsed XML document with one root element. Keeps the text so that a reader's messages
// can give the line of any node.
class XmlDocument {
 public:
  // Parses `text`; `origin` names it in messages ("'dir/a.vtp'"). Throws IoError
  // "<origin>: line L (offset O): malformed XML: <what>" for text that is not well-formed
  // XML with exactly one root element, and "<origin>: line L: XML elements nested deeper than
  // 64 levels ..." for a document deeper than kMaxXmlDepth (checked without recursion).
  XmlDocument(std::string_view text, std::string origin);
  XmlDocument(const XmlDocument&) = delete;
  XmlDocument& operator=(const XmlDocument&) = delete;

  pugi::xml_node root() const { return doc_.document_element(); }
  const std::string& origin() const { return origin_; }
  // The 1-based line of `node` in the text (for messages).
  std::size_t line(pugi::xml_node node) const;

 private:
  std::size_t line_at(std::size_t offset) const;

  std::string text_;
  std::string origin_;
  pugi::xml_document doc_;
};

// The character data directly inside `node` (entities decoded; comments skipped).
std::string xml_text(pugi::xml_node node);

// Escapes &, <, >, " and ' for use in attribute values and character data.
std::string xml_escape(std::string_view s);

}  // namespace invasim
