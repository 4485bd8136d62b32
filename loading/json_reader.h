#pragma once
// Strict reading of JSON scene descriptions. Every value is read through a JsonValue that knows
// its file and JSON pointer; every object through a JsonObject that records which keys the reader
// asked for, so finish() can reject the rest (a typo such as "albdo" is an error, never a silently
// ignored default). Errors are tyndall::Error with one line:
//     <file>: <JSON pointer>: expected <what>, got <what was there>
// e.g. "scenes/fog.json: /media/0/sigma_s: expected a finite number >= 0 or [r, g, b], got -0.5".
// Not thread-safe (JsonObject mutates its key record); documents are read on one thread.
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/math.h"

namespace tyndall {

class JsonObject;

/// Parses `text` (comments allowed); syntax errors throw Error "<file>: line L, column C: ...".
nlohmann::json parseJsonText(const std::string& text, const std::string& file);
/// One line from a nlohmann::json exception message about `text`, position first when known.
std::string jsonErrorText(const std::string& what, const std::string& text);

/// One value in a document plus where it is, for messages.
class JsonValue {
public:
    JsonValue(const nlohmann::json& value, std::string file, std::string pointer);

    const nlohmann::json& raw() const { return *m_value; }
    const std::string& file() const { return m_file; }
    /// JSON pointer of this value ("" for the document root).
    const std::string& pointer() const { return m_pointer; }
    /// "<file>: <pointer>" (or "<file>: top level"): the prefix of every message about this value.
    std::string where() const;
    /// Throws Error "<where>: <message>".
    [[noreturn]] void fail(const std::string& message) const;
    /// Short description of the value for "got ..." ("a string", "-0.5", "an array of 2").
    std::string describe() const;

    bool isString() const { return m_value->is_string(); }
    bool isNumber() const { return m_value->is_number(); }
    bool isInteger() const { return m_value->is_number_integer(); }
    bool isArray() const { return m_value->is_array(); }
    bool isObject() const { return m_value->is_object(); }

    /// A finite number in [lo, hi].
    double number(double lo = -1e30, double hi = 1e30) const;
    /// An integer in [lo, hi].
    int64_t integer(int64_t lo, int64_t hi) const;
    std::string string() const;
    bool boolean() const;
    /// [x, y, z], finite.
    Vec3 vec3() const;
    /// A non-zero [x, y, z] (directions, axes).
    Vec3 direction() const;
    /// A finite number >= lo (grey) or [r, g, b] with every channel finite and >= lo.
    Rgb rgb(float lo = 0.0f) const;
    JsonObject object() const;
    /// The elements of an array (throws when this is not an array).
    std::vector<JsonValue> elements() const;

private:
    [[noreturn]] void expected(const std::string& what) const;

    const nlohmann::json* m_value;
    std::string m_file;
    std::string m_pointer;
};

/// A JSON object read key by key. Ask for every key the format defines (get() records the key
/// even when absent), then call finish() to reject keys nobody asked for.
class JsonObject {
public:
    explicit JsonObject(const JsonValue& value);

    const JsonValue& value() const { return m_value; }
    std::string where() const { return m_value.where(); }
    [[noreturn]] void fail(const std::string& message) const { m_value.fail(message); }

    /// The value of `key`, or nullopt when absent. Records `key` as known.
    std::optional<JsonValue> get(const std::string& key);
    /// The value of `key`; throws "<where>: missing required key '<key>'" when absent.
    JsonValue require(const std::string& key);
    bool has(const std::string& key) const { return m_value.raw().contains(key); }

    // Shorthands: the value of `key` or `fallback` when absent (range checks as in JsonValue).
    double number(const std::string& key, double fallback, double lo = -1e30, double hi = 1e30);
    int64_t integer(const std::string& key, int64_t fallback, int64_t lo, int64_t hi);
    std::string string(const std::string& key, const std::string& fallback);
    bool boolean(const std::string& key, bool fallback);
    Vec3 vec3(const std::string& key, const Vec3& fallback);
    Rgb rgb(const std::string& key, const Rgb& fallback, float lo = 0.0f);

    /// Throws on the first key that was never asked for, listing the keys this object accepts.
    void finish() const;

private:
    JsonValue m_value;
    std::set<std::string> m_known;
};

/// Appends `key` to a JSON pointer with the RFC 6901 escapes.
std::string jsonPointerAppend(const std::string& pointer, const std::string& key);

}  // namespace tyndall
