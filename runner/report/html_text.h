#pragma once
// Text that goes into the page: every string from a results.json passes through here, so that
// nothing from the input can become markup.
#include <string>

namespace shadowcts {

// Escapes & < > " ' for element text and quoted attribute values alike (HTML, inline SVG and the
// JUnit XML), and replaces control characters XML cannot represent by spaces.
std::string html_escape(const std::string& text);

// A relative file path as a URL path: bytes other than unreserved characters and '/' are
// percent-encoded, so '#', '?', '%' and spaces in names cannot change what the browser loads.
std::string url_path(const std::string& relative_path);

}  // namespace shadowcts
