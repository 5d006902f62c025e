// Text helpers for the XML result writers (VTU, PVD, XDMF): escaping, base64, exact numbers.
#pragma once

#include <cstddef>
#include <string>

namespace tmlab {

/// XML-escapes &, <, >, " and ' so the text is safe in attribute values and element content.
std::string xml_escape(const std::string& text);

/// Base64 (RFC 4648 alphabet, with '=' padding) of `size` bytes; used for VTK binary DataArrays.
std::string base64_encode(const void* data, std::size_t size);

/// Shortest text that reads back to exactly `value` ("0.1", "1e-300", "nan", "inf").
std::string format_double(double value);

}  // namespace tmlab
