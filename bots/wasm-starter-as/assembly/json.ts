// A small JSON reader: enough of RFC 8259 for the server's requests
// (objects, arrays, strings with escapes, numbers, true/false/null), into a
// tree of `Json` values. Anything malformed, or nested deeper than
// MAX_DEPTH, gives null rather than a trap.

export enum Kind {
  Null,
  Bool,
  Number,
  String,
  Array,
  Object,
}

export class Json {
  kind: Kind = Kind.Null;
  bool: bool = false;
  num: f64 = 0;
  str: string = "";
  /** An array's items, or an object's values (keys beside them). */
  items: Json[] = [];
  keys: string[] = [];

  /** An object's value under `key`, or null. */
  get(key: string): Json | null {
    if (this.kind != Kind.Object) return null;
    for (let i = 0; i < this.keys.length; i++) {
      if (this.keys[i] == key) return this.items[i];
    }
    return null;
  }
}

const MAX_DEPTH = 64;

/** The value `text` holds, or null when it is not one JSON value. */
export function parse(text: string): Json | null {
  const p = new Parser(text);
  const v = p.value(0);
  if (v == null || !p.ok) return null;
  p.space();
  return p.i == text.length ? v : null;
}

class Parser {
  s: string;
  i: i32 = 0;
  ok: bool = true;

  constructor(s: string) {
    this.s = s;
  }

  fail(): Json | null {
    this.ok = false;
    return null;
  }

  peek(): i32 {
    return this.i < this.s.length ? this.s.charCodeAt(this.i) : -1;
  }

  space(): void {
    while (this.i < this.s.length) {
      const c = this.s.charCodeAt(this.i);
      if (c != 0x20 && c != 0x0a && c != 0x0d && c != 0x09) break;
      this.i++;
    }
  }

  word(w: string): bool {
    if (this.s.substr(this.i, w.length) != w) return false;
    this.i += w.length;
    return true;
  }

  value(depth: i32): Json | null {
    if (depth > MAX_DEPTH) return this.fail();
    this.space();
    const c = this.peek();
    const v = new Json();
    if (c == 0x7b /* { */) {
      this.i++;
      v.kind = Kind.Object;
      this.space();
      if (this.peek() == 0x7d) {
        this.i++;
        return v;
      }
      while (true) {
        this.space();
        if (this.peek() != 0x22) return this.fail();
        const key = this.string();
        if (!this.ok) return null;
        this.space();
        if (this.peek() != 0x3a /* : */) return this.fail();
        this.i++;
        const item = this.value(depth + 1);
        if (item == null) return null;
        v.keys.push(key);
        v.items.push(item);
        this.space();
        const d = this.peek();
        this.i++;
        if (d == 0x7d /* } */) return v;
        if (d != 0x2c /* , */) return this.fail();
      }
    }
    if (c == 0x5b /* [ */) {
      this.i++;
      v.kind = Kind.Array;
      this.space();
      if (this.peek() == 0x5d) {
        this.i++;
        return v;
      }
      while (true) {
        const item = this.value(depth + 1);
        if (item == null) return null;
        v.items.push(item);
        this.space();
        const d = this.peek();
        this.i++;
        if (d == 0x5d /* ] */) return v;
        if (d != 0x2c) return this.fail();
      }
    }
    if (c == 0x22 /* " */) {
      v.kind = Kind.String;
      v.str = this.string();
      return this.ok ? v : null;
    }
    if (this.word("true")) {
      v.kind = Kind.Bool;
      v.bool = true;
      return v;
    }
    if (this.word("false")) {
      v.kind = Kind.Bool;
      return v;
    }
    if (this.word("null")) return v;
    // A number: the longest run of number characters, parsed as a whole.
    const start = this.i;
    while (this.i < this.s.length) {
      const n = this.s.charCodeAt(this.i);
      const digit = n >= 0x30 && n <= 0x39;
      if (!digit && n != 0x2d && n != 0x2b && n != 0x2e && n != 0x65 && n != 0x45) break;
      this.i++;
    }
    if (this.i == start) return this.fail();
    v.kind = Kind.Number;
    v.num = parseFloat(this.s.substring(start, this.i));
    return isFinite(v.num) ? v : this.fail();
  }

  /** A string at `i` (on its opening quote), escapes decoded. */
  string(): string {
    this.i++;
    let out = "";
    let run = this.i;
    while (this.i < this.s.length) {
      const c = this.s.charCodeAt(this.i);
      if (c == 0x22) {
        out += this.s.substring(run, this.i);
        this.i++;
        return out;
      }
      if (c == 0x5c /* \ */) {
        out += this.s.substring(run, this.i);
        this.i++;
        const e = this.peek();
        this.i++;
        if (e == 0x6e) out += "\n";
        else if (e == 0x74) out += "\t";
        else if (e == 0x72) out += "\r";
        else if (e == 0x62) out += "\b";
        else if (e == 0x66) out += "\f";
        else if (e == 0x22 || e == 0x5c || e == 0x2f) out += String.fromCharCode(e);
        else if (e == 0x75 /* u */ && this.i + 4 <= this.s.length) {
          let code = 0;
          for (let k = 0; k < 4; k++) {
            const h = this.s.charCodeAt(this.i + k);
            let d = -1;
            if (h >= 0x30 && h <= 0x39) d = h - 0x30;
            else if (h >= 0x61 && h <= 0x66) d = h - 0x61 + 10;
            else if (h >= 0x41 && h <= 0x46) d = h - 0x41 + 10;
            if (d < 0) {
              this.ok = false;
              return "";
            }
            code = code * 16 + d;
          }
          out += String.fromCharCode(code);
          this.i += 4;
        } else {
          this.ok = false;
          return "";
        }
        run = this.i;
        continue;
      }
      this.i++;
    }
    this.ok = false;
    return "";
  }
}
