import js from '@eslint/js';
import globals from 'globals';

export default [
	{ ignores: [ 'web/dist/**', 'node_modules/**', '.venv/**', 'assets/**' ] },
	js.configs.recommended,
	{
		files: [ 'web/src/**/*.js' ],
		languageOptions: { ecmaVersion: 2022, sourceType: 'module', globals: globals.browser },
	},
	{
		files: [ 'tests/js/**/*.js', 'e2e/**/*.js', 'bench/**/*.mjs', 'scripts/**/*.mjs', 'web/vite.config.js' ],
		languageOptions: { ecmaVersion: 2022, sourceType: 'module', globals: { ...globals.node, ...globals.browser } },
	},
];
