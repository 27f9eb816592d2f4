// The page's messages that the library also words: filled from templates cut out of the
// library's own messages at build time (web/gen/constants.cpp), so both say the same thing.
import { messages } from 'prt:constants';

/** A template's {key}s replaced by values[key]. */
export function fill(template, values) {
  return template.replace(/\{([a-z]+)\}/g, (m, key) => (key in values ? String(values[key]) : m));
}

/** bands::bandLimitMessage: "WHAT has B bands; WHO takes 1..MAX". */
export function bandLimitMessage(what, bands, who, max) {
  return fill(messages.bandLimit, { what, bands, who, max });
}

/** io::loadLighting's warning for a light of `light` bands under a transfer of `transfer`. */
export function lightBandsWarning(name, light, transfer) {
  return fill(messages.lightBands, { name, light, transfer });
}
