#include "io/xml.hpp"

#include <algorithm>

#include "io/io_error.hpp"

namespace invasim {

namespace {

// Whether a failed parse stopped inside an element (the text ended before its end tag).
bool elements_open(const pugi::xml_parse_result& r) {
  return r.status == pugi::status_end_element_mismatch ||
         r.status == pugi::status_bad_start_element || r.status == pugi::status_bad_pcdata ||
         r.status == pugi::status_bad_attribute || r.status == pugi::status_bad_end_element;
}

pugi::xml_node first_element(pugi::xml_node n) {
  for (pugi::xml_node c = n.first_child(); c; c = c.next_sibling())
    if (c.type() == pugi::node_element) return c;
  return {};
}
pugi::xml_node next_element(pugi::xml_node n) {
  for (pugi::xml_node c = n.next_sibling(); c; c = c.next_sibling())
    if (c.type() == pugi::node_element) return c;
  return {};
}

// The first element nested deeper than kMaxXmlDepth (a walk in document order without
// recursion), or an empty node.
pugi::xml_node too_deep(pugi::xml_node root) {
  int depth = 1;
  pugi::xml_node n = root;
  for (;;) {
    if (depth > kMaxXmlDepth) return n;
    if (const pugi::xml_node c = first_element(n)) {
      n = c;
      ++depth;
      continue;
    }
    for (;;) {  // up to the nearest ancestor-or-self with a later sibling
      if (n == root) return {};
      if (const pugi::xml_node s = next_element(n)) {
        n = s;
        break;
      }
      n = n.parent();
      --depth;
    }
  }
}

}  // namespace

XmlDocument::XmlDocument(std::string_view text, std::string origin)
    : text_(text), origin_(std::move(origin)) {
  const pugi::xml_parse_result r = doc_.load_buffer(text_.data(), text_.size());
  auto fail = [&](std::size_t offset, const char* what) {
    const char* end = offset + 1 >= text_.size() && elements_open(r)
                          ? "; the text ends inside an element (a truncated file?)"
                          : "";
    fail_io(origin_, ": line ", line_at(offset), " (offset ", offset, "): malformed XML: ", what,
            end);
  };
  if (!r) fail(std::size_t(r.offset), r.description());
  // pugixml accepts fragments; an XML document has one root element and nothing else.
  int elements = 0;
  for (pugi::xml_node n : doc_.children()) {
    if (n.type() == pugi::node_element && ++elements == 1) continue;
    if (n.type() == pugi::node_element || n.type() == pugi::node_pcdata ||
        n.type() == pugi::node_cdata)
      fail(std::size_t(n.offset_debug()), "content after the root element");
  }
  if (const pugi::xml_node deep = too_deep(root()))
    fail_io(origin_, ": line ", line(deep), ": XML elements nested deeper than ", kMaxXmlDepth,
            " levels (the limit of invasim's VTK reader; its files nest 5)");
}

std::size_t XmlDocument::line_at(std::size_t offset) const {
  offset = std::min(offset, text_.size());
  return 1 + std::size_t(std::count(text_.begin(), text_.begin() + offset, '\n'));
}

std::size_t XmlDocument::line(pugi::xml_node node) const {
  const std::ptrdiff_t offset = node.offset_debug();
  return offset < 0 ? 0 : line_at(std::size_t(offset));
}

std::string xml_text(pugi::xml_node node) {
  std::string out;
  for (pugi::xml_node c : node.children())
    if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) out += c.value();
  return out;
}

std::string xml_escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  return out;
}

}  // namespace invasim
