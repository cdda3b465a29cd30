// Collects script errors, rejected promises, console errors and Content-Security-Policy
// violations into window.editorErrors (and body[data-errors]) so that tests and people can
// see them. A classic script, loaded before the modules, so it catches their failures too.
"use strict";
(function () {
  const errors = [];
  window.editorErrors = errors;
  function note(text) {
    errors.push(String(text));
    if (document.body) {
      document.body.dataset.errors = JSON.stringify(errors);
    }
  }
  window.addEventListener("error", function (event) {
    note("error: " + (event.message || (event.target && event.target.src) || "resource failed"));
  }, true);
  window.addEventListener("unhandledrejection", function (event) {
    note("unhandled rejection: " + (event.reason && event.reason.message || event.reason));
  });
  document.addEventListener("securitypolicyviolation", function (event) {
    note("CSP violation: " + event.violatedDirective + " " + event.blockedURI);
  });
  const consoleError = console.error.bind(console);
  console.error = function (...args) {
    note("console.error: " + args.map(String).join(" "));
    consoleError(...args);
  };
})();
