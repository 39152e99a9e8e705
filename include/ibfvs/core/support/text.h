#pragma once
// Parsing of the small text forms that scenes, specs and command lines share:
// "X,Y,Z", comma lists, whole numbers, "a:b:c" specs. Messages name the text
// that is wrong, never an option: the caller knows which setting it was and
// adds its name (SettingError), the command line its flag.

#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace ibfvs {

/// Splits "a:b:c" at its colons (the form of field and generated-mesh specs).
std::vector<std::string> split_colons(std::string_view text);

/// Comma-separated finite numbers. Throws InputError for a part that is not a
/// finite number, or when `count` > 0 and the number of parts differs
/// (`expected` then describes the form, e.g. "X,Y,Z").
std::vector<float> parse_numbers(std::string_view text, std::size_t count = 0,
                                 std::string_view expected = "");

/// "X,Y,Z": three finite numbers. Throws InputError.
glm::vec3 parse_vec3(std::string_view text);

/// A whole number in [lo, hi]. Throws InputError.
long long parse_integer(std::string_view text, long long lo, long long hi);

/// A finite number (the whole text). Throws InputError.
double parse_number(std::string_view text);

/// "X,Y,Z" with the shortest text that reads back as the same floats.
std::string format_vec3(const glm::vec3& v);

/// The shortest text that reads back as the same float.
std::string format_number(double v);

/// A piece of an input's text for a message, in quotes: control and other
/// unprintable bytes become '?', and past `max` characters it is cut with
/// "..." (a file's binary junk must not break the message's one line).
std::string excerpt(std::string_view text, std::size_t max = 40);

/// Shell-style match of a whole name: `*` any run of characters, `?` one.
bool glob_match(std::string_view pattern, std::string_view text);

}  // namespace ibfvs
