// A problem document of the API (RFC 9457) as one readable message. Its field errors name
// JSON pointers into the editor's request; when the curve came from a text the designer
// pasted or opened, they are turned into the line, column and pointer of that text instead.

import { locate, positionOf, syntaxErrorAt } from "./jsonsource.js";

/** serde's " at line 1 column 69": a place in the editor's request, not in the user's text. */
const REQUEST_POSITION = /\s+at line \d+ column \d+$/;

/**
 * Where the curve of a request came from: the user's `text`, and the pointer of the curve
 * inside it (`""` when the text is the curve itself, `"/curve"` when it holds one).
 */
export function textSource(text, curvePointer) {
  return { text, curvePointer };
}

/** The place a request pointer (under `/curve`) names in the source text, in words. */
function placeInText(pointer, source) {
  if (!source || !pointer.startsWith("/curve")) return null;
  const own = source.curvePointer + pointer.slice("/curve".length);
  try {
    const position = locate(source.text, own);
    return position ? `line ${position.line}, column ${position.column} (${own || "/"})` : null;
  } catch {
    return own;
  }
}

/**
 * One line for `problem`: each field error as "where: what" (the place in the user's text
 * when `source` is given), else the title and detail. Nothing is said twice.
 */
export function describeProblem(problem, source = null) {
  const errors = problem.errors || [];
  if (errors.length > 0) {
    return errors
      .map((error) => {
        const pointer = error.pointer || "";
        const where = placeInText(pointer, source) ?? (pointer || "the request");
        return `${where}: ${(error.detail || problem.title).replace(REQUEST_POSITION, "")}`;
      })
      .join("; ");
  }
  const detail = (problem.detail || "").replace(REQUEST_POSITION, "");
  return detail && detail !== problem.title ? `${problem.title}: ${detail}` : problem.title;
}

/** Why `text` (which JSON.parse refused) is not JSON: "line L, column C: unexpected …". */
export function describeSyntaxError(text) {
  const offset = syntaxErrorAt(text) ?? text.length;
  const { line, column } = positionOf(text, offset);
  const what = offset >= text.length ? "the text ends too early" : `unexpected ${JSON.stringify(text[offset])}`;
  return `line ${line}, column ${column}: ${what}`;
}
