#pragma once
// A minimal XML reader and an escaping helper, enough for the VTK XML files this layer writes
// (.vtp, .pvd): elements, attributes, character data, comments, the <?xml?> prolog and the
// five predefined entities. No namespaces, DTDs or CDATA: a file that uses them is refused
// with a message naming the file and line.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace invasim {

struct XmlElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<XmlElement> children;
  std::string text;  // character data directly inside this element, entities decoded
  std::size_t line = 0;

  // The attribute's value, or nullptr.
  const std::string* attribute(std::string_view key) const;
  // The first child with this name, or nullptr.
  const XmlElement* child(std::string_view child_name) const;
  std::vector<const XmlElement*> children_named(std::string_view child_name) const;
};

// Parses a document; returns its root element. Throws IoError naming `origin` and the line.
XmlElement parse_xml(std::string_view text, const std::string& origin);

// Escapes &, <, >, " and ' for use in attribute values and character data.
std::string xml_escape(std::string_view s);

}  // namespace invasim
