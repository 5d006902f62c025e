// Test helper: a tiny, strict XML reader (elements, attributes, text; no DTDs, comments or CDATA)
// used to check that the writers' XML is well formed and to pull counts and values back out.
#pragma once

#include <cctype>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace tmlab::test {

struct XmlNode {
  std::string tag;
  std::map<std::string, std::string> attrs;
  std::string text;  ///< concatenated character data directly inside this element
  std::vector<std::unique_ptr<XmlNode>> children;

  /// All descendants (and self) with this tag, in document order.
  void find_all(const std::string& t, std::vector<const XmlNode*>& out) const {
    if (tag == t) out.push_back(this);
    for (const auto& c : children) c->find_all(t, out);
  }
  std::vector<const XmlNode*> all(const std::string& t) const {
    std::vector<const XmlNode*> out;
    find_all(t, out);
    return out;
  }
  std::string attr(const std::string& k) const {
    const auto it = attrs.find(k);
    if (it == attrs.end()) throw std::runtime_error("<" + tag + "> has no attribute " + k);
    return it->second;
  }
};

inline std::string xml_unescape(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '&') {
      out += s[i];
      continue;
    }
    const auto semi = s.find(';', i);
    if (semi == std::string::npos) throw std::runtime_error("bad entity");
    const std::string e = s.substr(i + 1, semi - i - 1);
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
      throw std::runtime_error("unknown entity &" + e + ";");
    i = semi;
  }
  return out;
}

/// Parses a document (optional <?xml ...?> prolog, one root element); throws on malformed input.
inline std::unique_ptr<XmlNode> parse_xml(const std::string& s) {
  std::size_t i = 0;
  const auto skip_ws = [&] {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  };
  const auto name = [&] {
    const std::size_t b = i;
    while (i < s.size() && (std::isalnum(static_cast<unsigned char>(s[i])) || s[i] == '_' || s[i] == ':' ||
                            s[i] == '-' || s[i] == '.'))
      ++i;
    if (b == i) throw std::runtime_error("expected a name at offset " + std::to_string(b));
    return s.substr(b, i - b);
  };
  skip_ws();
  if (s.compare(i, 5, "<?xml") == 0) {
    const auto e = s.find("?>", i);
    if (e == std::string::npos) throw std::runtime_error("unterminated prolog");
    i = e + 2;
  }
  std::vector<XmlNode*> stack;
  std::unique_ptr<XmlNode> root;
  while (true) {
    if (stack.empty()) skip_ws();
    if (i >= s.size()) break;
    if (s[i] != '<') {
      if (stack.empty()) throw std::runtime_error("text outside the root element");
      const auto e = s.find('<', i);
      if (e == std::string::npos)
        throw std::runtime_error("unterminated element <" + stack.back()->tag + ">");
      stack.back()->text += xml_unescape(s.substr(i, e - i));
      i = e;
      continue;
    }
    ++i;
    if (i < s.size() && s[i] == '/') {
      ++i;
      const std::string t = name();
      skip_ws();
      if (i >= s.size() || s[i] != '>') throw std::runtime_error("bad end tag </" + t);
      ++i;
      if (stack.empty() || stack.back()->tag != t) throw std::runtime_error("mismatched </" + t + ">");
      stack.pop_back();
      continue;
    }
    auto node = std::make_unique<XmlNode>();
    node->tag = name();
    while (true) {
      skip_ws();
      if (i >= s.size()) throw std::runtime_error("unterminated tag <" + node->tag);
      if (s[i] == '>' || s[i] == '/') break;
      const std::string k = name();
      skip_ws();
      if (s[i] != '=') throw std::runtime_error("expected = after " + k);
      ++i;
      skip_ws();
      const char q = s[i];
      if (q != '"' && q != '\'') throw std::runtime_error("unquoted attribute " + k);
      const auto e = s.find(q, i + 1);
      if (e == std::string::npos) throw std::runtime_error("unterminated attribute " + k);
      if (node->attrs.count(k)) throw std::runtime_error("duplicate attribute " + k);
      node->attrs[k] = xml_unescape(s.substr(i + 1, e - i - 1));
      i = e + 1;
    }
    bool self_closing = false;
    if (s[i] == '/') {
      self_closing = true;
      ++i;
      if (i >= s.size() || s[i] != '>') throw std::runtime_error("bad empty tag <" + node->tag);
    }
    ++i;
    XmlNode* raw = node.get();
    if (stack.empty()) {
      if (root) throw std::runtime_error("second root element <" + node->tag + ">");
      root = std::move(node);
    } else {
      stack.back()->children.push_back(std::move(node));
    }
    if (!self_closing) stack.push_back(raw);
  }
  if (!stack.empty()) throw std::runtime_error("unclosed <" + stack.back()->tag + ">");
  if (!root) throw std::runtime_error("no root element");
  return root;
}

/// Decodes RFC 4648 base64 (whitespace ignored); throws on invalid characters.
inline std::vector<std::uint8_t> base64_decode(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : text) {
    if (std::isspace(static_cast<unsigned char>(c))) continue;
    if (c == '=') break;
    int v;
    if (c >= 'A' && c <= 'Z')
      v = c - 'A';
    else if (c >= 'a' && c <= 'z')
      v = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      v = c - '0' + 52;
    else if (c == '+')
      v = 62;
    else if (c == '/')
      v = 63;
    else
      throw std::runtime_error(std::string("bad base64 character ") + c);
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((acc >> bits) & 0xFF));
    }
  }
  return out;
}

}  // namespace tmlab::test
