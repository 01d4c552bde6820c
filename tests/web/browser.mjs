// Debian's chromium, headless, through puppeteer-core (DevTools protocol), with WebGL2 on
// SwiftShader (the flags issue 29 checked), and a page opener that records every console
// message and page error, so the test can fail on any of them.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import puppeteer from 'puppeteer-core';

export const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';

/// Launches chromium with a fresh profile; `width`x`height` is the page's viewport.
export async function launch({width = 1280, height = 800} = {}) {
  if (!fs.existsSync(CHROMIUM)) {
    throw new Error(`${CHROMIUM} not found: apt-get install chromium (or set CHROMIUM=...)`);
  }
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'formsim-chromium-'));
  const browser = await puppeteer.launch({
    executablePath: CHROMIUM,
    headless: true,  // puppeteer passes --headless=new
    userDataDir: profile,
    defaultViewport: {width, height},
    protocolTimeout: 600000,  // runHeadless of a long scenario blocks the page for a while
    args: [
      '--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      `--window-size=${width},${height}`,
      // Root in a container has no sandbox; the machine's network is closed, so nothing may
      // call home (each refused connection would be a console error otherwise).
      '--no-sandbox', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync', '--disable-quic',
      '--disable-default-apps', '--disable-extensions',
      // Tabs the test is not looking at keep their animation frames (formsim's main loop).
      '--disable-background-timer-throttling', '--disable-renderer-backgrounding',
      '--disable-backgrounding-occluded-windows',
    ],
  });
  const close = async () => {
    await browser.close();
    fs.rmSync(profile, {recursive: true, force: true});
  };
  return {browser, close};
}

/// Opens `url` in a new tab (`downloads`: a folder the browser saves downloads into;
/// `beforeLoad`: a function run in the page before its scripts). Returns {page, log, problems()}: `log` holds every console
/// message ({type, text}) and page error; problems() lists the errors (console.error, page
/// errors, failed requests) — warnings, where formsim's stderr goes, are allowed.
export async function open(browser, url, {downloads, beforeLoad} = {}) {
  const page = await browser.newPage();
  if (beforeLoad) await page.evaluateOnNewDocument(beforeLoad);
  const log = [];
  page.on('console', (m) => log.push({type: m.type(), text: m.text()}));
  page.on('pageerror', (e) => log.push({type: 'pageerror', text: String(e && e.message || e)}));
  page.on('requestfailed', (r) => log.push({
    type: 'requestfailed', text: `${r.url()}: ${r.failure() && r.failure().errorText}`,
  }));
  page.on('response', (r) => {
    if (r.status() >= 400) log.push({type: 'httperror', text: `${r.status()} ${r.url()}`});
  });
  if (downloads) {
    const cdp = await page.createCDPSession();
    await cdp.send('Browser.setDownloadBehavior', {behavior: 'allow', downloadPath: downloads});
  }
  await page.goto(url, {waitUntil: 'load'});
  const problems = () =>
    log.filter((e) => ['error', 'assert', 'pageerror', 'requestfailed', 'httperror'].includes(e.type));
  return {page, log, problems};
}
