#include "loading/json_reader.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"

namespace tyndall {

std::string jsonErrorText(const std::string& what, const std::string& text) {
    // nlohmann's messages look like "[json.exception.parse_error.101] parse error at line 3,
    // column 14: syntax error ..." or "[json.exception.out_of_range.406] number overflow parsing '1e999'".
    std::string msg = what;
    if (msg.rfind("[json.exception", 0) == 0 && msg.find("] ") != std::string::npos)
        msg = msg.substr(msg.find("] ") + 2);
    auto at = msg.find("parse error at line ");
    if (at != std::string::npos) msg = msg.substr(at + 15);
    const std::string overflow = "number overflow parsing '";
    if (msg.rfind(overflow, 0) == 0 && msg.back() == '\'') {
        // No position in this one: find the literal in the text.
        std::string literal = msg.substr(overflow.size(), msg.size() - overflow.size() - 1);
        size_t pos = literal.empty() ? std::string::npos : text.find(literal);
        if (pos != std::string::npos) {
            size_t line = 1 + size_t(std::count(text.begin(), text.begin() + long(pos), '\n'));
            size_t newline = pos == 0 ? std::string::npos : text.rfind('\n', pos - 1);
            size_t column = pos - (newline == std::string::npos ? 0 : newline + 1) + 1;
            msg = "line " + std::to_string(line) + ", column " + std::to_string(column) + ": number overflow: '" +
                  literal + "' is not a finite number";
        }
    }
    for (char& c : msg)
        if (c == '\n' || c == '\r') c = ' ';
    return msg;
}

nlohmann::json parseJsonText(const std::string& text, const std::string& file) {
    try {
        return nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
    } catch (const nlohmann::json::exception& e) {
        throw Error(file + ": " + jsonErrorText(e.what(), text));
    }
}

std::string jsonPointerAppend(const std::string& pointer, const std::string& key) {
    std::string out = pointer + "/";
    for (char c : key) {
        if (c == '~')
            out += "~0";
        else if (c == '/')
            out += "~1";
        else
            out += c;
    }
    return out;
}

JsonValue::JsonValue(const nlohmann::json& value, std::string file, std::string pointer)
    : m_value(&value), m_file(std::move(file)), m_pointer(std::move(pointer)) {}

std::string JsonValue::where() const {
    return m_file + ": " + (m_pointer.empty() ? "top level" : m_pointer);
}

void JsonValue::fail(const std::string& message) const {
    throw Error(where() + ": " + message);
}

std::string JsonValue::describe() const {
    const nlohmann::json& j = *m_value;
    switch (j.type()) {
        case nlohmann::json::value_t::null:
            return "null";
        case nlohmann::json::value_t::boolean:
            return j.get<bool>() ? "true" : "false";
        case nlohmann::json::value_t::string: {
            std::string s = j.get<std::string>();
            if (s.size() > 40) s = s.substr(0, 40) + "...";
            for (char& c : s)
                if (c < 32) c = ' ';
            return "the string \"" + s + "\"";
        }
        case nlohmann::json::value_t::number_integer:
        case nlohmann::json::value_t::number_unsigned:
        case nlohmann::json::value_t::number_float: {
            std::ostringstream s;
            s << j.get<double>();
            return s.str();
        }
        case nlohmann::json::value_t::array:
            return "an array of " + std::to_string(j.size());
        case nlohmann::json::value_t::object:
            return "an object";
        default:
            return "an unsupported value";
    }
}

void JsonValue::expected(const std::string& what) const {
    fail("expected " + what + ", got " + describe());
}

namespace {
std::string rangeText(double lo, double hi) {
    std::ostringstream s;
    if (lo <= -1e30 && hi >= 1e30) return "";
    if (hi >= 1e30)
        s << " >= " << lo;
    else if (lo <= -1e30)
        s << " <= " << hi;
    else
        s << " in [" << lo << ", " << hi << "]";
    return s.str();
}
}  // namespace

double JsonValue::number(double lo, double hi) const {
    std::string want = "a finite number" + rangeText(lo, hi);
    if (!m_value->is_number()) expected(want);
    double v = m_value->get<double>();
    if (!std::isfinite(v) || v < lo || v > hi) expected(want);
    return v;
}

int64_t JsonValue::integer(int64_t lo, int64_t hi) const {
    std::string want = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!m_value->is_number_integer()) expected(want);
    if (m_value->is_number_unsigned() && m_value->get<uint64_t>() > uint64_t(INT64_MAX)) expected(want);
    int64_t v = m_value->get<int64_t>();
    if (v < lo || v > hi) expected(want);
    return v;
}

std::string JsonValue::string() const {
    if (!m_value->is_string()) expected("a string");
    return m_value->get<std::string>();
}

bool JsonValue::boolean() const {
    if (!m_value->is_boolean()) expected("true or false");
    return m_value->get<bool>();
}

Vec3 JsonValue::vec3() const {
    const char* want = "[x, y, z] with finite numbers";
    if (!m_value->is_array() || m_value->size() != 3) expected(want);
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
        const nlohmann::json& e = (*m_value)[size_t(i)];
        if (!e.is_number() || !std::isfinite(e.get<double>()))
            JsonValue(e, m_file, jsonPointerAppend(m_pointer, std::to_string(i))).expected("a finite number");
        v[i] = float(e.get<double>());
    }
    return v;
}

Vec3 JsonValue::direction() const {
    Vec3 v = vec3();
    if (!(length(v) > 1e-12f)) fail("expected a non-zero direction, got [0, 0, 0]");
    return v;
}

Rgb JsonValue::rgb(float lo) const {
    std::ostringstream want;
    want << "a finite number >= " << lo << " or [r, g, b]";
    if (m_value->is_number()) {
        double v = m_value->get<double>();
        if (!std::isfinite(v) || v < lo) expected(want.str());
        return Rgb(float(v));
    }
    if (!m_value->is_array() || m_value->size() != 3) expected(want.str());
    Rgb c;
    for (int i = 0; i < 3; ++i) {
        const nlohmann::json& e = (*m_value)[size_t(i)];
        JsonValue at(e, m_file, jsonPointerAppend(m_pointer, std::to_string(i)));
        c[i] = float(at.number(lo));
    }
    return c;
}

JsonObject JsonValue::object() const {
    return JsonObject(*this);
}

std::vector<JsonValue> JsonValue::elements() const {
    if (!m_value->is_array()) expected("an array");
    std::vector<JsonValue> out;
    for (size_t i = 0; i < m_value->size(); ++i)
        out.emplace_back((*m_value)[i], m_file, jsonPointerAppend(m_pointer, std::to_string(i)));
    return out;
}

JsonObject::JsonObject(const JsonValue& value) : m_value(value) {
    if (!value.isObject()) value.fail("expected an object {...}, got " + value.describe());
}

std::optional<JsonValue> JsonObject::get(const std::string& key) {
    m_known.insert(key);
    auto it = m_value.raw().find(key);
    if (it == m_value.raw().end()) return std::nullopt;
    return JsonValue(*it, m_value.file(), jsonPointerAppend(m_value.pointer(), key));
}

JsonValue JsonObject::require(const std::string& key) {
    auto v = get(key);
    if (!v) fail("missing required key '" + key + "'");
    return *v;
}

double JsonObject::number(const std::string& key, double fallback, double lo, double hi) {
    auto v = get(key);
    return v ? v->number(lo, hi) : fallback;
}

int64_t JsonObject::integer(const std::string& key, int64_t fallback, int64_t lo, int64_t hi) {
    auto v = get(key);
    return v ? v->integer(lo, hi) : fallback;
}

std::string JsonObject::string(const std::string& key, const std::string& fallback) {
    auto v = get(key);
    return v ? v->string() : fallback;
}

bool JsonObject::boolean(const std::string& key, bool fallback) {
    auto v = get(key);
    return v ? v->boolean() : fallback;
}

Vec3 JsonObject::vec3(const std::string& key, const Vec3& fallback) {
    auto v = get(key);
    return v ? v->vec3() : fallback;
}

Rgb JsonObject::rgb(const std::string& key, const Rgb& fallback, float lo) {
    auto v = get(key);
    return v ? v->rgb(lo) : fallback;
}

void JsonObject::finish() const {
    for (auto it = m_value.raw().begin(); it != m_value.raw().end(); ++it) {
        if (m_known.count(it.key())) continue;
        std::string known;
        for (const std::string& k : m_known) known += (known.empty() ? "" : ", ") + k;
        JsonValue(it.value(), m_value.file(), jsonPointerAppend(m_value.pointer(), it.key()))
            .fail("unknown key '" + it.key() + "'" + (known.empty() ? "" : " (expected one of: " + known + ")"));
    }
}

}  // namespace tyndall
