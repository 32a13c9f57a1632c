// Checks xAPI statement files with Learning Locker's validator (@learninglocker/xapi-validation).
// Usage: node validate.js FILE...   Prints "FILE: ok" or "FILE: PATH: WARNING" per problem;
// exits 1 when any file has a problem.
'use strict';
const fs = require('fs');
const validate = require('@learninglocker/xapi-validation').default;

let bad = 0;
for (const file of process.argv.slice(2)) {
  let warnings;
  try {
    warnings = validate(JSON.parse(fs.readFileSync(file, 'utf8')));
  } catch (e) {
    warnings = [{ path: [], message: String(e.message || e) }];
  }
  if (warnings.length === 0) {
    console.log(`${file}: ok`);
    continue;
  }
  bad += 1;
  for (const w of warnings) console.log(`${file}: ${(w.path || []).join('.')}: ${w.name || ''} ${w.message || ''}`.trim());
}
process.exit(bad === 0 ? 0 : 1);
