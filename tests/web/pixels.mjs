// Pixel checks of a screenshot of formsim's window: is the world drawn, with the robots'
// colours? Reads the PNG formsim wrote (its `screenshot` action) with pngjs.
import {PNG} from 'pngjs';

/// The first robots' colours: sim::PaletteColor(0..2) (sim/core/draw.cpp), as the light and
/// dark themes fill robot bodies and draw trails.
export const ROBOT_COLOURS = {R1: [0x00, 0x72, 0xb2], R2: [0xd5, 0x5e, 0x00], R3: [0x00, 0x9e, 0x73]};

/// The world view at the page's 1280x800: the window's two-column layout (issue 46: the world
/// view keeps at least half the window), the tabs on the left (420 px), the world view right of
/// them, below the menu bar and above the timeline.
export function worldRegion(width, height) {
  return {x0: Math.round(0.34 * width), x1: Math.round(0.99 * width),
          y0: Math.round(0.06 * height), y1: Math.round(0.94 * height)};
}

/// Decodes `png` (a Buffer or Uint8Array) and measures `region` (default: worldRegion):
/// {width, height, background: [r,g,b], nonBackground (fraction of the region's pixels that
/// are not its most frequent colour), robots: {R1: pixels within `tolerance` per channel, ...}}.
export function measureWorld(png, {region, tolerance = 24} = {}) {
  const img = PNG.sync.read(Buffer.from(png));
  const {width, height, data} = img;
  const r = region || worldRegion(width, height);
  const counts = new Map();
  const robots = Object.fromEntries(Object.keys(ROBOT_COLOURS).map((k) => [k, 0]));
  let total = 0;
  for (let y = r.y0; y < r.y1; ++y) {
    for (let x = r.x0; x < r.x1; ++x) {
      const i = 4 * (y * width + x);
      const key = (data[i] << 16) | (data[i + 1] << 8) | data[i + 2];
      counts.set(key, (counts.get(key) || 0) + 1);
      ++total;
      for (const [name, c] of Object.entries(ROBOT_COLOURS)) {
        if (Math.abs(data[i] - c[0]) <= tolerance && Math.abs(data[i + 1] - c[1]) <= tolerance &&
            Math.abs(data[i + 2] - c[2]) <= tolerance) {
          ++robots[name];
        }
      }
    }
  }
  let bgKey = 0;
  let bgCount = -1;
  for (const [k, n] of counts) if (n > bgCount) [bgKey, bgCount] = [k, n];
  return {
    width, height, region: r,
    background: [bgKey >> 16, (bgKey >> 8) & 255, bgKey & 255],
    nonBackground: total ? 1 - bgCount / total : 0,
    robots,
  };
}
