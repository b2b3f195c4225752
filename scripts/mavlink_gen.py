#!/usr/bin/env python3
"""Generate comms/mavlink/messages.hpp from resources/mavlink/irgs.xml and the official XML.

The official definitions it includes are read from ../shared/mavlink/ (not copied here).

The output is committed, so building IRGS needs no Python; rerun this after editing a
definition or the message list below:

    python3 scripts/mavlink_gen.py            # writes comms/mavlink/messages.hpp
    python3 scripts/mavlink_gen.py --check    # exit 1 if the committed header is stale

Each message also gets kFields, a table of its numeric values (name, XML unit, type, wire
offset, array element; comms/mavlink/field_info.hpp reads a decoded frame through it) and
setField(index, value) to fill the struct by table index.

Wire rules (https://mavlink.io/en/guide/serialization.html):
  * base fields are sent sorted by the size of their element type, largest first (stable sort,
    so fields of the same size keep their XML order); extension fields follow, in XML order;
  * CRC_EXTRA = X.25 CRC over "NAME " then, per base field in wire order, "type " "name " and,
    for arrays, one byte holding the array length; folded to 8 bits as (crc & 0xFF) ^ (crc >> 8).
"""

import argparse
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
XML_DIR = os.path.join(ROOT, "resources", "mavlink")
# The official definitions are not copied into the project (see shared/mavlink/README.md): an
# include not found beside irgs.xml is read from the shared folder next to the repository.
OFFICIAL_DIR = os.path.join(os.path.dirname(ROOT), "shared", "mavlink")


def xml_path(name):
    beside = os.path.join(XML_DIR, name)
    return beside if os.path.exists(beside) else os.path.join(OFFICIAL_DIR, name)
OUT = os.path.join(ROOT, "comms", "mavlink", "messages.hpp")
TOP_XML = "irgs.xml"
MAVLINK_VERSION = 3  # <version> of common.xml, which irgs.xml inherits

# Messages the project exchanges (docs/protocol.md says who sends each one and how often).
MESSAGES = [
    "HEARTBEAT", "SYS_STATUS", "STATUSTEXT", "COMMAND_LONG", "COMMAND_ACK",
    "PARAM_REQUEST_LIST", "PARAM_REQUEST_READ", "PARAM_VALUE", "PARAM_SET", "TIMESYNC",
    "MANUAL_CONTROL", "DISTANCE_SENSOR", "RAW_IMU", "SCALED_IMU", "ATTITUDE", "WHEEL_DISTANCE",
    "ODOMETRY", "LOCAL_POSITION_NED", "MISSION_REQUEST_LIST", "MISSION_COUNT",
    "MISSION_REQUEST_INT", "MISSION_ITEM_INT", "MISSION_ACK", "MISSION_CLEAR_ALL",
    "MISSION_CURRENT", "MISSION_ITEM_REACHED", "IRGS_STEREO_SONAR", "IRGS_ENCODER_TICKS",
    "IRGS_CONTACT", "IRGS_BEHAVIOUR_STATUS", "IRGS_SONAR_SCAN", "IRGS_POSE_2D", "IRGS_MOUSE_COUNTS",
    "IRGS_CASTER_ENCODERS", "IRGS_MOTION_REPORT", "IRGS_WAYPOINTS",
]

# Enums generated as `enum class`; MAV_CMD is restricted to the commands the project uses.
ENUMS = [
    "MAV_TYPE", "MAV_AUTOPILOT", "MAV_MODE_FLAG", "MAV_STATE", "MAV_COMPONENT", "MAV_SEVERITY",
    "MAV_RESULT", "MAV_PARAM_TYPE", "MAV_FRAME", "MAV_MISSION_TYPE", "MAV_MISSION_RESULT",
    "MAV_DISTANCE_SENSOR", "MAV_SENSOR_ORIENTATION", "MAV_ESTIMATOR_TYPE", "MAV_CMD",
    "IRGS_WALL_SIDE", "IRGS_BEHAVIOUR_STATE", "IRGS_SONAR_FLAGS", "IRGS_MOUSE_STATUS",
    "IRGS_CASTER_FLAGS", "IRGS_PRIMITIVE_KIND", "IRGS_MOTION_REPORT_KIND", "IRGS_MOTION_REASON",
    "IRGS_MOTION_FLAGS",
]
MAV_CMD_USED = [
    "MAV_CMD_NAV_WAYPOINT", "MAV_CMD_DO_SET_MODE", "MAV_CMD_COMPONENT_ARM_DISARM",
    "MAV_CMD_SET_MESSAGE_INTERVAL", "MAV_CMD_REQUEST_MESSAGE", "MAV_CMD_MISSION_START",
    "MAV_CMD_IRGS_MOVE_DISTANCE", "MAV_CMD_IRGS_TURN_ANGLE", "MAV_CMD_IRGS_FOLLOW_WALL",
    "MAV_CMD_IRGS_STOP", "MAV_CMD_IRGS_EMERGENCY_STOP",
]

# MAVLink type -> FieldType enumerator (comms/mavlink/field_info.hpp); char is text, not numeric.
FIELD_TYPES = {
    "uint8_t": "kUint8", "int8_t": "kInt8", "uint16_t": "kUint16", "int16_t": "kInt16",
    "uint32_t": "kUint32", "int32_t": "kInt32", "uint64_t": "kUint64", "int64_t": "kInt64",
    "float": "kFloat", "double": "kDouble",
}

TYPES = {  # MAVLink type -> (C++ type, size in bytes)
    "char": ("char", 1), "uint8_t": ("std::uint8_t", 1), "int8_t": ("std::int8_t", 1),
    "uint16_t": ("std::uint16_t", 2), "int16_t": ("std::int16_t", 2),
    "uint32_t": ("std::uint32_t", 4), "int32_t": ("std::int32_t", 4),
    "uint64_t": ("std::uint64_t", 8), "int64_t": ("std::int64_t", 8),
    "float": ("float", 4), "double": ("double", 8),
    "uint8_t_mavlink_version": ("std::uint8_t", 1),
}


def x25(data, crc=0xFFFF):
    for b in data:
        tmp = (b ^ (crc & 0xFF)) & 0xFF
        tmp = (tmp ^ (tmp << 4)) & 0xFF
        crc = ((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4)) & 0xFFFF
    return crc


class Field:
    def __init__(self, el, extension):
        text = el.get("type")
        self.name = el.get("name")
        self.extension = extension
        self.array = 0
        if "[" in text:
            text, n = text[:-1].split("[")
            self.array = int(n)
        # The "mavlink_version" pseudo type is uint8_t on the wire and in CRC_EXTRA.
        self.magic = text == "uint8_t_mavlink_version"
        self.wire_type = "uint8_t" if self.magic else text
        self.cpp, self.size = TYPES[text]
        self.units = el.get("units", "")
        self.instance = el.get("instance", "") == "true"
        self.enum = el.get("enum", "")
        self.doc = " ".join((el.text or "").split())


class Message:
    def __init__(self, el, source):
        self.id = int(el.get("id"))
        self.name = el.get("name")
        self.source = source
        self.doc = " ".join((el.findtext("description") or "").split())
        self.fields = []
        extension = False
        for child in el:
            if child.tag == "extensions":
                extension = True
            elif child.tag == "field":
                self.fields.append(Field(child, extension))
        base = [f for f in self.fields if not f.extension]
        self.wire = sorted(base, key=lambda f: -f.size) + [f for f in self.fields if f.extension]
        offset = 0
        for f in self.wire:
            f.offset = offset
            offset += f.size * max(1, f.array)
        self.max_length = offset
        self.min_length = sum(f.size * max(1, f.array) for f in base)
        crc = x25((self.name + " ").encode())
        for f in base_sorted(base):
            crc = x25((f.wire_type + " ").encode(), crc)
            crc = x25((f.name + " ").encode(), crc)
            if f.array:
                crc = x25(bytes([f.array]), crc)
        self.crc_extra = (crc & 0xFF) ^ (crc >> 8)


def base_sorted(base):
    return sorted(base, key=lambda f: -f.size)


def load(name, messages, enums, seen):
    if name in seen:
        return
    seen.add(name)
    root = ET.parse(xml_path(name)).getroot()
    for inc in root.findall("include"):
        load(inc.text.strip(), messages, enums, seen)
    for en in root.iter("enum"):
        entries = enums.setdefault(en.get("name"), [])
        for e in en.findall("entry"):
            entries.append((e.get("name"), int(e.get("value")), " ".join(
                (e.findtext("description") or "").split())))
    for m in root.iter("message"):
        messages[m.get("name")] = Message(m, name)


def camel(name):
    return "".join(p[:1] + p[1:].lower() for p in name.split("_"))


def wrap_comment(text, indent, width=100):
    words = text.split()
    lines, line = [], indent + "//"
    for w in words:
        if len(line) + 1 + len(w) > width and line != indent + "//":
            lines.append(line)
            line = indent + "//"
        line += " " + w
    if line != indent + "//":
        lines.append(line)
    return lines


def emit_enum(name, entries, out):
    if name == "MAV_CMD":
        entries = [e for e in entries if e[0] in MAV_CMD_USED]
    prefix = name + "_"
    if not all(e[0].startswith(prefix) for e in entries):
        # e.g. MAV_COMPONENT entries are MAV_COMP_ID_*: strip the common "_" prefix instead.
        parts = [e[0].split("_") for e in entries]
        common = []
        for group in zip(*parts):
            if len(set(group)) != 1:
                break
            common.append(group[0])
        prefix = "_".join(common) + "_"
    biggest = max(v for _, v, _ in entries)
    under = "std::uint8_t" if biggest < 256 else "std::uint16_t" if biggest < 65536 else "std::uint32_t"
    out.append(f"enum class {camel(name)} : {under} {{")
    for ename, value, _ in entries:
        out.append(f"  k{camel(ename[len(prefix):])} = {value},")
    out.append("};")
    out.append("")


def emit_message(m, out):
    cls = camel(m.name)
    out.extend(wrap_comment(f"{m.name} ({m.source}): {m.doc}", ""))
    out.append(f"struct {cls} {{")
    out.append(f"  static constexpr std::uint32_t kId = {m.id};")
    out.append(f"  static constexpr std::string_view kName = \"{m.name}\";")
    out.append(f"  static constexpr std::uint8_t kCrcExtra = {m.crc_extra};")
    out.append(f"  static constexpr std::uint8_t kMinLength = {m.min_length};  // base fields only")
    out.append(f"  static constexpr std::uint8_t kMaxLength = {m.max_length};  // with extensions")
    out.append("")
    for f in m.fields:
        extras = []
        if f.units:
            extras.append(f"[{f.units}]")
        if f.enum:
            extras.append(f"({f.enum})")
        if f.extension:
            extras.append("(extension)")
        doc = " ".join(extras + [f.doc])
        # The magic mavlink_version field defaults to the protocol version of the definitions.
        init = MAVLINK_VERSION if f.magic else 0
        decl = f"std::array<{f.cpp}, {f.array}> {f.name}{{}};" if f.array else f"{f.cpp} {f.name} = {init};"
        line = f"  {decl}  // {doc}"
        if len(line) <= 100:
            out.append(line)
        else:
            out.extend(wrap_comment(doc, "  "))
            out.append(f"  {decl}")
    out.append("")
    out.append("  // Writes all kMaxLength bytes (untrimmed); the frame encoder trims trailing zeros.")
    out.append("  void pack(std::span<std::uint8_t, kMaxLength> out) const {")
    for f in m.wire:
        if f.array:
            out.append(f"    wire::putArray(out.data() + {f.offset}, {f.name});")
        else:
            out.append(f"    wire::put(out.data() + {f.offset}, {f.name});")
    out.append("  }")
    out.append("  // Bytes beyond payload.size() read as zero (MAVLink 2 re-extension of trimmed payloads).")
    out.append(f"  static {cls} unpack(std::span<const std::uint8_t> payload) {{")
    out.append(f"    {cls} m;")
    for f in m.wire:
        if f.array:
            out.append(f"    wire::getArray(payload, {f.offset}, m.{f.name});")
        else:
            out.append(f"    wire::get(payload, {f.offset}, m.{f.name});")
    out.append("    return m;")
    out.append("  }")
    emit_field_table(m, out)
    out.append(f"  friend bool operator==(const {cls}&, const {cls}&) = default;")
    out.append("};")
    out.append("")


def numeric_elements(m):
    """(field, element index or -1) of every numeric value, in declaration order."""
    for f in m.fields:
        if f.wire_type == "char":
            continue
        for i in range(f.array) if f.array else [-1]:
            yield f, i


def emit_field_table(m, out):
    elements = list(numeric_elements(m))
    out.append("  // Every numeric value (arrays element by element; char text left out), in declaration")
    out.append("  // order, with its byte offset in the wire-order payload: readField() reads a decoded")
    out.append("  // frame's payload through it, setField() fills this struct by table index.")
    out.append(f"  static constexpr std::array<FieldInfo, {len(elements)}> kFields{{{{")
    for f, i in elements:
        offset = f.offset + f.size * max(0, i)
        instance = "true" if f.instance else "false"
        extension = "true" if f.extension else "false"
        out.append(f"      {{\"{f.name}\", \"{f.units}\", FieldType::{FIELD_TYPES[f.wire_type]}, {offset}, {i}, "
                   f"{instance}, {extension}}},")
    out.append("  }};")
    out.append("  // Sets kFields[field_number] to `value` (converted to the field's type); false when out of range.")
    # Named so that no message field (IRGS_MOTION_REPORT.index) is shadowed.
    out.append("  constexpr bool setField(std::size_t field_number, double value) {")
    out.append("    switch (field_number) {")
    for n, (f, i) in enumerate(elements):
        target = f"{f.name}[{i}]" if i >= 0 else f.name
        out.append(f"      case {n}: {target} = static_cast<{f.cpp}>(value); return true;")
    out.append("      default: return false;")
    out.append("    }")
    out.append("  }")


def generate():
    messages, enums = {}, {}
    load(TOP_XML, messages, enums, set())
    out = [
        "#pragma once",
        "// GENERATED by scripts/mavlink_gen.py from resources/mavlink/irgs.xml (+ official XML) -- do not edit.",
        "// Typed MAVLink messages: fields in declaration (XML) order, packed in wire order (sorted by",
        "// element size, extensions last). Enum-typed fields keep their raw integer type so unknown",
        "// values survive a round trip; the enums below name the values the project uses.",
        "",
        "#include <array>",
        "#include <cstddef>",
        "#include <cstdint>",
        "#include <span>",
        "#include <string_view>",
        "#include <tuple>",
        "",
        "#include \"comms/mavlink/field_info.hpp\"",
        "#include \"comms/mavlink/message_info.hpp\"",
        "#include \"comms/mavlink/wire.hpp\"",
        "",
        "namespace irgs::comms::mavlink {",
        "",
    ]
    for name in ENUMS:
        emit_enum(name, enums[name], out)
    chosen = [messages[n] for n in MESSAGES]
    for m in chosen:
        emit_message(m, out)
    out.append("// Every generated message, sorted by id (findMessageInfo searches it).")
    out.append(f"inline constexpr std::array<MessageInfo, {len(chosen)}> kGeneratedMessages{{{{")
    for m in sorted(chosen, key=lambda m: m.id):
        cls = camel(m.name)
        out.append(f"    messageInfoOf<{cls}>(),")
    out.append("}};")
    out.append("")
    out.append("// Every generated message's field table, sorted by id (findMessageFields searches it).")
    out.append(f"inline constexpr std::array<MessageFields, {len(chosen)}> kGeneratedMessageFields{{{{")
    for m in sorted(chosen, key=lambda m: m.id):
        out.append(f"    messageFieldsOf<{camel(m.name)}>(),")
    out.append("}};")
    out.append("")
    out.append("// Every generated message type, for code that handles all of them (tests, dispatch).")
    out.append("using GeneratedMessageTypes = std::tuple<")
    names = [camel(m.name) for m in chosen]
    for i, n in enumerate(names):
        out.append(f"    {n}{',' if i + 1 < len(names) else '>;'}")
    out.append("")
    out.append("}  // namespace irgs::comms::mavlink")
    text = "\n".join(out) + "\n"
    # Formatted like the hand-written sources (repository .clang-format) when clang-format exists.
    if shutil.which("clang-format"):
        text = subprocess.run(["clang-format", "--assume-filename=" + OUT], input=text,
                              capture_output=True, text=True, check=True, cwd=ROOT).stdout
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="fail if the header is stale")
    parser.add_argument("--print-crc", action="store_true", help="print id name crc_extra")
    args = parser.parse_args()
    text = generate()
    if args.print_crc:
        messages, enums = {}, {}
        load(TOP_XML, messages, enums, set())
        for n in MESSAGES:
            m = messages[n]
            print(m.id, n, m.crc_extra, m.min_length, m.max_length)
        return 0
    if args.check:
        with open(OUT) as f:
            if f.read() != text:
                print(f"{OUT} is stale: run python3 scripts/mavlink_gen.py", file=sys.stderr)
                return 1
        return 0
    with open(OUT, "w") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
