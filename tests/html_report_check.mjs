// Opens an HTML report in headless Chromium with every request that would leave the machine blocked, and
// prints one JSON object with what test_html_report.cpp checks: console errors, blocked requests, whether
// the canvas shows more than one colour, the rows of the table, whether sorting by a column works, and how
// many pixels clicking the first row changed.
// Usage: node html_report_check.mjs --modules NODE_MODULES --page REPORT.html [--sort COLUMN] [--screenshot OUT.png]
// Chromium: $CHROMIUM or /usr/bin/chromium (WebGL through SwiftShader). Exit status 0 when it could look
// (the checks are the caller's), 2 when it could not (no Chromium, the page never got ready).
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';
import { pathToFileURL } from 'node:url';

const options = { modules: null, page: null, sort: null, screenshot: null };
const args = process.argv.slice(2);
for (let i = 0; i < args.length; ++i) {
    const key = args[i].replace(/^--/, '');
    if (!(key in options) || i + 1 >= args.length) {
        console.error('usage: node html_report_check.mjs --modules DIR --page FILE [--sort COLUMN] [--screenshot OUT.png]');
        process.exit(2);
    }
    options[key] = args[++i];
}
const puppeteer = createRequire(path.join(path.resolve(options.modules), 'noop.js'))('puppeteer-core');

let browser;
try {
    browser = await puppeteer.launch({
        executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
        headless: true,
        args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
               '--disable-dev-shm-usage', '--window-size=1280,860'],
        defaultViewport: { width: 1280, height: 860, deviceScaleFactor: 1 },
        protocolTimeout: 300000,
    });
} catch (error) {
    console.error(`html_report_check: cannot start Chromium: ${error.message.split('\n')[0]}`);
    process.exit(2);
}

const result = { consoleErrors: [], blockedRequests: [], pageBytes: fs.statSync(options.page).size };
try {
    const page = await browser.newPage();
    // Only what stays on the machine may load: the file itself and what it makes in memory.
    await page.setRequestInterception(true);
    page.on('request', (request) => {
        if (/^(file|data|blob|about):/.test(request.url())) return request.continue();
        result.blockedRequests.push(request.url());
        return request.abort('blockedbyclient');
    });
    page.on('console', (message) => {
        if (message.type() === 'error') result.consoleErrors.push(message.text());
    });
    page.on('pageerror', (error) => result.consoleErrors.push(String(error.message || error)));

    const start = Date.now();
    await page.goto(pathToFileURL(path.resolve(options.page)).href, { waitUntil: 'load', timeout: 120000 });
    await page.waitForFunction('window.symcompressReport && window.symcompressReport.ready === true', { timeout: 120000 });
    result.loadMilliseconds = Date.now() - start;

    // The canvas's pixels (the renderer keeps its drawing buffer), read through a 2D canvas.
    const pixels = () => page.evaluate(() => {
        const source = document.getElementById('scene');
        const copy = document.createElement('canvas');
        copy.width = source.width;
        copy.height = source.height;
        const context = copy.getContext('2d');
        context.drawImage(source, 0, 0);
        return Array.from(context.getImageData(0, 0, copy.width, copy.height).data);
    });
    const distinctColors = (rgba) => {
        const seen = new Set();
        for (let i = 0; i < rgba.length && seen.size < 1000; i += 4) seen.add((rgba[i] << 16) | (rgba[i + 1] << 8) | rgba[i + 2]);
        return seen.size;
    };
    const before = await pixels();
    result.distinctColors = distinctColors(before);
    result.rows = await page.evaluate(() => document.querySelectorAll('#classes tbody tr').length);
    result.rowsReported = await page.evaluate(() => window.symcompressReport.classesShown);

    // Sorting: a click on the column's heading orders the rows by it.
    if (options.sort) {
        const column = await page.evaluate((title) =>
            [...document.querySelectorAll('#classes thead th')].findIndex((th) => th.textContent === title), options.sort);
        result.sortColumnFound = column >= 0;
        if (column >= 0) {
            await page.click(`#classes thead th:nth-child(${column + 1})`);
            const values = await page.evaluate((c) => [...document.querySelectorAll('#classes tbody tr')]
                .map((tr) => Number(tr.children[c].textContent)), column);
            result.sortedDescending = values.every((v, i) => i === 0 || values[i - 1] >= v);
            result.firstRowAfterSort = values[0];
        }
    }
    // Clicking the first row changes the picture (its members highlighted, its elements drawn).
    if (result.rows > 0) {
        await page.click('#classes tbody tr:first-child');
        const after = await pixels();
        let changed = 0;
        for (let i = 0; i < after.length; i += 4)
            if (after[i] !== before[i] || after[i + 1] !== before[i + 1] || after[i + 2] !== before[i + 2]) ++changed;
        result.changedPixels = changed;
        result.selection = await page.evaluate(() => document.getElementById('selection').textContent);
    }
    if (options.screenshot) await page.screenshot({ path: options.screenshot, fullPage: true });
} catch (error) {
    console.error(`html_report_check: ${error.message || error}`);
    await browser.close();
    process.exit(2);
}
await browser.close();
console.log(JSON.stringify(result));
