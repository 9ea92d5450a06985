#include "io/xml.hpp"

#include "io/io_error.hpp"

namespace invasim {

const std::string* XmlElement::attribute(std::string_view key) const {
  for (const auto& [k, v] : attributes)
    if (k == key) return &v;
  return nullptr;
}

const XmlElement* XmlElement::child(std::string_view child_name) const {
  for (const XmlElement& c : children)
    if (c.name == child_name) return &c;
  return nullptr;
}

std::vector<const XmlElement*> XmlElement::children_named(std::string_view child_name) const {
  std::vector<const XmlElement*> out;
  for (const XmlElement& c : children)
    if (c.name == child_name) out.push_back(&c);
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

namespace {

// Recursive-descent parser over the whole text.
class Parser {
 public:
  Parser(std::string_view text, const std::string& origin) : s_(text), origin_(origin) {}

  XmlElement document() {
    skip_misc();
    if (!starts_with("<")) fail("no root element");
    XmlElement root = element();
    skip_misc();
    if (pos_ < s_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    fail_io(origin_, ": line ", line(), ": malformed XML: ", what);
  }
  // Line of the current position, counted incrementally (positions only move forward).
  std::size_t line() {
    for (; counted_ < pos_ && counted_ < s_.size(); ++counted_) line_ += s_[counted_] == '\n';
    return line_;
  }
  bool starts_with(std::string_view p) const { return s_.substr(pos_, p.size()) == p; }
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
  void skip_space() {
    while (pos_ < s_.size() && is_space(s_[pos_])) ++pos_;
  }
  void skip_past(std::string_view end) {
    const std::size_t k = s_.find(end, pos_);
    if (k == std::string_view::npos)
      fail("unterminated markup (missing '" + std::string(end) + "')");
    pos_ = k + end.size();
  }
  // Whitespace, comments and processing instructions between elements.
  void skip_misc() {
    while (true) {
      skip_space();
      if (starts_with("<?"))
        skip_past("?>");
      else if (starts_with("<!--"))
        skip_past("-->");
      else if (starts_with("<!"))
        fail("DTDs and CDATA sections are not supported");
      else
        return;
    }
  }
  std::string name() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() && !is_space(s_[pos_]) && s_[pos_] != '>' && s_[pos_] != '/' &&
           s_[pos_] != '=')
      ++pos_;
    if (pos_ == start) fail("expected a name");
    return std::string(s_.substr(start, pos_ - start));
  }
  std::string decode(std::string_view raw) {
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const std::size_t semi = raw.find(';', i);
      if (semi == std::string_view::npos) fail("unterminated entity");
      const std::string_view e = raw.substr(i + 1, semi - i - 1);
      if (e == "amp")
        out += '&';
      else if (e == "lt")
        out += '<';
      else if (e == "gt")
        out += '>';
      else if (e == "quot")
        out += '"';
      else if (e == "apos")
        out += '\'';
      else
        fail("unknown entity &" + std::string(e) + ";");
      i = semi;
    }
    return out;
  }
  XmlElement element() {
    XmlElement e;
    e.line = line();
    ++pos_;  // '<'
    e.name = name();
    while (true) {
      skip_space();
      if (pos_ >= s_.size()) fail("unterminated start tag <" + e.name + ">");
      if (starts_with("/>")) {
        pos_ += 2;
        return e;
      }
      if (s_[pos_] == '>') {
        ++pos_;
        break;
      }
      std::string key = name();
      skip_space();
      if (pos_ >= s_.size() || s_[pos_] != '=') fail("attribute " + key + " has no value");
      ++pos_;
      skip_space();
      if (pos_ >= s_.size() || (s_[pos_] != '"' && s_[pos_] != '\''))
        fail("attribute " + key + ": value must be quoted");
      const char quote = s_[pos_++];
      const std::size_t end = s_.find(quote, pos_);
      if (end == std::string_view::npos) fail("attribute " + key + ": unterminated value");
      e.attributes.emplace_back(std::move(key), decode(s_.substr(pos_, end - pos_)));
      pos_ = end + 1;
    }
    // Content: character data, children, comments, until </name>.
    while (true) {
      const std::size_t lt = s_.find('<', pos_);
      if (lt == std::string_view::npos) fail("element <" + e.name + "> is not closed");
      e.text += decode(s_.substr(pos_, lt - pos_));
      pos_ = lt;
      if (starts_with("</")) {
        pos_ += 2;
        if (name() != e.name) fail("mismatched end tag for <" + e.name + ">");
        skip_space();
        if (pos_ >= s_.size() || s_[pos_] != '>') fail("malformed end tag </" + e.name + ">");
        ++pos_;
        return e;
      }
      if (starts_with("<!--"))
        skip_past("-->");
      else if (starts_with("<?"))
        skip_past("?>");
      else if (starts_with("<!"))
        fail("DTDs and CDATA sections are not supported");
      else
        e.children.push_back(element());
    }
  }

  std::string_view s_;
  const std::string& origin_;
  std::size_t pos_ = 0, counted_ = 0, line_ = 1;
};

}  // namespace

XmlElement parse_xml(std::string_view text, const std::string& origin) {
  return Parser(text, origin).document();
}

}  // namespace invasim
