// Where things are in a JSON text: the line and column of the value a JSON pointer
// (RFC 6901) names, and of a character offset. Used to point an error of the API into the
// text the designer pasted or opened rather than into the editor's own request.

/** { line, column } (both from 1) of character `offset` of `text`. */
export function positionOf(text, offset) {
  let line = 1;
  let lineStart = 0;
  for (let i = 0; i < offset && i < text.length; i += 1) {
    if (text[i] === "\n") {
      line += 1;
      lineStart = i + 1;
    }
  }
  return { line, column: offset - lineStart + 1 };
}

const SPACE = " \t\n\r";

/**
 * The position of the value `pointer` names in `text` (valid JSON), or of the deepest
 * value on its way that exists (a missing member points at its object). Null when `text`
 * has no value at all.
 */
export function locate(text, pointer) {
  const tokens = pointer === "" ? [] : pointer.split("/").slice(1).map((t) => t.replace(/~1/g, "/").replace(/~0/g, "~"));
  let i = 0;
  const skipSpace = () => {
    while (i < text.length && SPACE.includes(text[i])) i += 1;
  };
  const skipString = () => {
    const start = i;
    i += 1;
    while (i < text.length && text[i] !== '"') i += text[i] === "\\" ? 2 : 1;
    i += 1;
    return JSON.parse(text.slice(start, i));
  };
  const skipValue = () => {
    if (text[i] === '"') {
      skipString();
      return;
    }
    if (text[i] === "{" || text[i] === "[") {
      let depth = 0;
      do {
        if (text[i] === '"') {
          skipString();
          continue;
        }
        if (text[i] === "{" || text[i] === "[") depth += 1;
        if (text[i] === "}" || text[i] === "]") depth -= 1;
        i += 1;
      } while (depth > 0 && i < text.length);
      return;
    }
    while (i < text.length && !",]}".includes(text[i]) && !SPACE.includes(text[i])) i += 1;
  };
  const next = () => {
    skipSpace();
    if (text[i] === ",") i += 1;
    skipSpace();
  };
  skipSpace();
  if (i >= text.length) return null;
  for (const token of tokens) {
    const container = i;
    if (text[i] === "{") {
      i += 1;
      skipSpace();
      let found = false;
      while (i < text.length && text[i] !== "}") {
        const key = skipString();
        skipSpace();
        i += 1; // the colon
        skipSpace();
        if (key === token) {
          found = true;
          break;
        }
        skipValue();
        next();
      }
      if (!found) return positionOf(text, container);
    } else if (text[i] === "[" && /^\d+$/.test(token)) {
      i += 1;
      skipSpace();
      for (let index = 0; index < Number(token); index += 1) {
        if (text[i] === "]") break;
        skipValue();
        next();
      }
      if (i >= text.length || text[i] === "]") return positionOf(text, container);
    } else {
      return positionOf(text, container);
    }
  }
  return positionOf(text, i);
}

/** Nesting deeper than this is reported as an error (no curve is that deep). */
const DEEPEST = 512;
const NUMBER = /-?(?:0|[1-9]\d*)(?:\.\d+)?(?:[eE][+-]?\d+)?/y;

/**
 * The offset of the first character that makes `text` invalid JSON (RFC 8259), or null
 * when it is valid. (JSON.parse's own messages do not always say where.)
 */
export function syntaxErrorAt(text) {
  let i = 0;
  const fail = () => {
    throw new RangeError(String(i));
  };
  const space = () => {
    while (i < text.length && SPACE.includes(text[i])) i += 1;
  };
  const string = () => {
    i += 1;
    while (i < text.length && text[i] !== '"') {
      if (text[i] < " ") fail();
      i += text[i] === "\\" ? 2 : 1;
    }
    if (i >= text.length) fail();
    i += 1;
  };
  const members = (close, member) => {
    i += 1;
    space();
    if (text[i] === close) {
      i += 1;
      return;
    }
    for (;;) {
      member();
      space();
      if (text[i] === ",") {
        i += 1;
      } else if (text[i] === close) {
        i += 1;
        return;
      } else {
        fail();
      }
    }
  };
  const value = (depth) => {
    if (depth > DEEPEST) fail();
    space();
    const c = text[i];
    if (c === "{") {
      members("}", () => {
        space();
        if (text[i] !== '"') fail();
        string();
        space();
        if (text[i] !== ":") fail();
        i += 1;
        value(depth + 1);
      });
    } else if (c === "[") {
      members("]", () => value(depth + 1));
    } else if (c === '"') {
      string();
    } else {
      NUMBER.lastIndex = i;
      const number = NUMBER.exec(text);
      if (number && number[0]) {
        i += number[0].length;
        return;
      }
      const word = ["true", "false", "null"].find((w) => text.startsWith(w, i));
      if (!word) fail();
      i += word.length;
    }
  };
  try {
    value(0);
    space();
    if (i < text.length) fail();
    return null;
  } catch (error) {
    if (error instanceof RangeError && /^\d+$/.test(error.message)) return Number(error.message);
    throw error;
  }
}
